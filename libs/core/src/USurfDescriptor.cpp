#include <mrpt_vslam/core/USurfDescriptor.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace mrpt_vslam::core {
namespace {

constexpr int kGrid = 20;          // samples per side of the 20s window
constexpr int kSamplesPerSub = 5;  // samples per side of a sub-region
constexpr int kSubRegions = kGrid / kSamplesPerSub;
constexpr double kSigmaInScale = 3.3;  // Gaussian σ of the weights, in units of s (Sec. 4.1)
constexpr int kCorners = kGrid + 2;    // box edges per side: x + (j − 10.5)s, j = 0..21

/// 1-D Gaussian factors exp(−u² / (2·3.3²)) of the sample offsets u = (i + ½) − 10 [units of s];
/// the 2-D weight of sample (r, c) is weight[r]·weight[c].
const std::array<double, kGrid>& sampleWeights()
{
    static const std::array<double, kGrid> weights = [] {
        std::array<double, kGrid> w;
        for (int i = 0; i < kGrid; i++) {
            const double u = i + 0.5 - 0.5 * kGrid;
            w[i] = std::exp(-u * u / (2 * kSigmaInScale * kSigmaInScale));
        }
        return w;
    }();
    return weights;
}

struct THaar {
    double dx;
    double dy;
};

/** Haar responses from the integrals F at the 3 × 3 box corners around a sample: f[r][c] at
 *  (x + (c − 1)s, y + (r − 1)s); `half_area` = 2s² [mean gray levels]. */
template <typename Corners>
THaar haarFromCorners(const Corners& f, int r, int c, double half_area)
{
    // Box sum over rows [r0, r1) and columns [c0, c1) of the corner grid.
    const auto box = [&](int r0, int c0, int r1, int c1) {
        return f[r1][c1] - f[r1][c0] - f[r0][c1] + f[r0][c0];
    };
    return {(box(r, c + 1, r + 2, c + 2) - box(r, c, r + 2, c + 1)) / half_area,
            (box(r + 1, c, r + 2, c + 2) - box(r, c, r + 1, c + 2)) / half_area};
}

/// Integrals at the 3 × 3 corners of the 2s box centred on (x, y).
std::array<std::array<double, 3>, 3> boxCorners(const IntegralImage& ii, double x, double y,
                                                double s)
{
    std::array<std::array<double, 3>, 3> f;
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++) f[r][c] = ii.integralAt(x + (c - 1) * s, y + (r - 1) * s);
    }
    return f;
}
void checkKeypoint(double x, double y, double scale)
{
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(scale) || !(scale > 0)) {
        throw std::invalid_argument("USurfDescriptor: bad keypoint (x=" + std::to_string(x) +
                                    ", y=" + std::to_string(y) +
                                    ", scale=" + std::to_string(scale) + ")");
    }
}

}  // namespace

USurfDescriptor::USurfDescriptor(const mrpt::img::CImage& image) : m_integral(image) {}

bool USurfDescriptor::fitsInImage(double x, double y, double scale) const
{
    checkKeypoint(x, y, scale);
    // Outermost box edges at ±10.5s; pixel c spans [c − ½, c + ½).
    const double reach = 0.5 * (kCorners - 1) * scale;
    return x - reach >= -0.5 && x + reach <= m_integral.width() - 0.5 && y - reach >= -0.5 &&
           y + reach <= m_integral.height() - 0.5;
}

double USurfDescriptor::haarX(double x, double y, double scale) const
{
    return haarFromCorners(boxCorners(m_integral, x, y, scale), 0, 0, 2 * scale * scale).dx;
}

double USurfDescriptor::haarY(double x, double y, double scale) const
{
    return haarFromCorners(boxCorners(m_integral, x, y, scale), 0, 0, 2 * scale * scale).dy;
}

std::optional<USurfDescriptor::TDescriptor> USurfDescriptor::compute(double x, double y,
                                                                     double scale) const
{
    if (!fitsInImage(x, y, scale)) return std::nullopt;
    const auto& weight = sampleWeights();
    // Integrals at the shared box corners x + (j − 10.5)s, y + (i − 10.5)s.
    std::array<double, kCorners> xs;
    std::array<double, kCorners> ys;
    for (int j = 0; j < kCorners; j++) {
        xs[j] = x + (j - 0.5 * kCorners + 0.5) * scale;
        ys[j] = y + (j - 0.5 * kCorners + 0.5) * scale;
    }
    std::array<std::array<double, kCorners>, kCorners> f;
    for (int i = 0; i < kCorners; i++) {
        for (int j = 0; j < kCorners; j++) f[i][j] = m_integral.integralAt(xs[j], ys[i]);
    }
    const double half_area = 2 * scale * scale;
    std::array<double, kSize> v{};
    for (int r = 0; r < kGrid; r++) {
        for (int c = 0; c < kGrid; c++) {
            // Sample (r, c) at offset ((c + ½) − 10, (r + ½) − 10)·s: corners r..r+2, c..c+2.
            const THaar haar = haarFromCorners(f, r, c, half_area);
            // Gaussian weight, σ = 3.3s, centred on the keypoint (Sec. 4.1).
            const double w = weight[r] * weight[c];
            const double dx = w * haar.dx;
            const double dy = w * haar.dy;
            // v = (Σdx, Σdy, Σ|dx|, Σ|dy|) of the sub-region (Sec. 4.1).
            double* sub = &v[4 * (kSubRegions * (r / kSamplesPerSub) + c / kSamplesPerSub)];
            sub[0] += dx;
            sub[1] += dy;
            sub[2] += std::abs(dx);
            sub[3] += std::abs(dy);
        }
    }
    double norm2 = 0;
    for (double e : v) norm2 += e * e;
    if (!(norm2 > 0)) return std::nullopt;
    const double inv_norm = 1.0 / std::sqrt(norm2);
    TDescriptor out;
    for (size_t k = 0; k < kSize; k++) out[k] = static_cast<float>(v[k] * inv_norm);
    return out;
}

double USurfDescriptor::distance(const TDescriptor& a, const TDescriptor& b)
{
    double d2 = 0;
    for (size_t k = 0; k < kSize; k++) {
        const double d = static_cast<double>(a[k]) - b[k];
        d2 += d * d;
    }
    return std::sqrt(d2);
}

std::optional<USurfDescriptor::TMatch> USurfDescriptor::bestMatch(
    const TDescriptor& query, const std::vector<TDescriptor>& candidates, double ratio)
{
    if (!(ratio > 0 && ratio <= 1)) {
        throw std::invalid_argument("USurfDescriptor::bestMatch: ratio must be in (0, 1], got " +
                                    std::to_string(ratio));
    }
    if (candidates.empty()) return std::nullopt;
    TMatch match;
    match.distance = std::numeric_limits<double>::infinity();
    match.second_distance = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < candidates.size(); i++) {
        const double d = distance(query, candidates[i]);
        if (d < match.distance) {
            match.second_distance = match.distance;
            match.distance = d;
            match.index = i;
        } else if (d < match.second_distance) {
            match.second_distance = d;
        }
    }
    // Lowe's ratio test (Lowe 2004, Sec. 7.1); trivially passed by a single candidate.
    if (candidates.size() > 1 && !(match.distance < ratio * match.second_distance)) {
        return std::nullopt;
    }
    return match;
}

}  // namespace mrpt_vslam::core
