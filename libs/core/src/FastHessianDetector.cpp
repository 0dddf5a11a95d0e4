#include <mrpt/config/CConfigFileBase.h>
#include <mrpt_vslam/core/FastHessianDetector.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/core/ParallelFor.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>

namespace mrpt_vslam::core {
namespace {

constexpr int kLayersPerOctave = 4;

/** Geometry of the box filters of size L (Fig. 1 for L = 9, scaled as in Sec. 3.3): lobes of
 *  l0 = L/3 along the derivative and 2·l0 − 1 across it; Dxy has four l0 × l0 lobes around a
 *  one-pixel cross. */
struct TBoxFilter {
    explicit TBoxFilter(int filter_size)
        : l0(filter_size / 3),
          half((filter_size - 1) / 2),
          across(l0 - 1),
          mid((l0 - 1) / 2),
          inv_area(1.0 / (double(filter_size) * filter_size))
    {
    }
    int l0;
    int half;         ///< half extent along the derivative
    int across;       ///< half width across it
    int mid;          ///< half extent of the central lobe
    double inv_area;  ///< 1 / L²: responses are normalised by the filter area (Sec. 3.3)
};

FastHessianDetector::THessian boxResponses(const IntegralImage& ii, int col, int row,
                                           const TBoxFilter& f)
{
    // Whole strip with weight 1 minus 3 × the central lobe: weights +1, −2, +1.
    const int64_t dyy =
        ii.boxSum(col - f.across, row - f.half, col + f.across + 1, row + f.half + 1) -
        3 * ii.boxSum(col - f.across, row - f.mid, col + f.across + 1, row + f.mid + 1);
    const int64_t dxx =
        ii.boxSum(col - f.half, row - f.across, col + f.half + 1, row + f.across + 1) -
        3 * ii.boxSum(col - f.mid, row - f.across, col + f.mid + 1, row + f.across + 1);
    // +1 where x and y have the same sign (top-left, bottom-right), −1 elsewhere.
    const int l0 = f.l0;
    const int64_t dxy = ii.boxSum(col - l0, row - l0, col, row) +
                        ii.boxSum(col + 1, row + 1, col + l0 + 1, row + l0 + 1) -
                        ii.boxSum(col + 1, row - l0, col + l0 + 1, row) -
                        ii.boxSum(col - l0, row + 1, col, row + l0 + 1);
    return {dxx * f.inv_area, dyy * f.inv_area, dxy * f.inv_area};
}

/// det(H) and the Laplacian sign of one filter size on a regular grid of the image.
struct TResponseLayer {
    int filter_size = 0;
    int step = 0;  ///< [px] grid spacing: sample (c, r) is pixel (c·step, r·step)
    int cols = 0;
    std::vector<float> det;                  ///< 0 where the filter leaves the image
    std::vector<int8_t> laplacian_positive;  ///< 1 where Dxx + Dyy > 0
};

TResponseLayer computeLayer(const IntegralImage& ii, int filter_size, int step, unsigned threads)
{
    TResponseLayer layer;
    layer.filter_size = filter_size;
    layer.step = step;
    layer.cols = (ii.width() - 1) / step + 1;
    const int rows = (ii.height() - 1) / step + 1;
    layer.det.assign(size_t(layer.cols) * rows, 0.f);
    layer.laplacian_positive.assign(layer.det.size(), 0);
    const TBoxFilter filter(filter_size);
    // First and last grid index whose filter lies inside the image.
    const int c0 = (filter.half + step - 1) / step, c1 = (ii.width() - 1 - filter.half) / step;
    const int r0 = (filter.half + step - 1) / step, r1 = (ii.height() - 1 - filter.half) / step;
    if (r1 < r0) return layer;
    parallelFor(size_t(r1 - r0 + 1), threads, [&](size_t i) {
        const int r = r0 + int(i);
        for (int c = c0; c <= c1; c++) {
            const auto h = boxResponses(ii, c * step, r * step, filter);
            const size_t k = size_t(r) * layer.cols + c;
            layer.det[k] = static_cast<float>(h.determinant());
            layer.laplacian_positive[k] = h.trace() > 0;
        }
    });
    return layer;
}

/// A response layer read on the (coarser or equal) grid of an octave.
struct TOctaveView {
    TOctaveView(const TResponseLayer& l, int octave_step) : layer(&l), ratio(octave_step / l.step)
    {
    }
    const TResponseLayer* layer;
    int ratio;  ///< octave step / layer step

    size_t index(int gx, int gy) const { return size_t(gy * ratio) * layer->cols + gx * ratio; }
    /// Response at octave grid point (gx, gy), i.e. pixel (gx·step, gy·step).
    double at(int gx, int gy) const { return layer->det[index(gx, gy)]; }
};

/** Keypoints of the middle layer of three consecutive layers `v` of an octave: thresholded
 *  3 × 3 × 3 maxima (Sec. 3.4) refined by the quadratic fit of Brown & Lowe (2002). */
void findMaxima(const std::array<TOctaveView, 3>& v, int step, int width, int height,
                double threshold, std::vector<FastHessianDetector::TKeypoint>& out)
{
    // The neighbourhood, including the largest filter, must lie inside the image.
    const int margin = (v[2].layer->filter_size - 1) / 2 + step;
    const int gx0 = (margin + step - 1) / step, gx1 = (width - 1 - margin) / step;
    const int gy0 = (margin + step - 1) / step, gy1 = (height - 1 - margin) / step;
    for (int gy = gy0; gy <= gy1; gy++) {
        for (int gx = gx0; gx <= gx1; gx++) {
            const double c = v[1].at(gx, gy);
            if (!(c > threshold)) continue;
            // R(dl, dy, dx): response of the neighbour at layer offset dl, row dy, column dx.
            const auto R = [&](int dl, int dy, int dx) { return v[1 + dl].at(gx + dx, gy + dy); };
            bool is_max = true;
            bool before = true;  // neighbours before the centre in (scale, row, col) order
            for (int dl = -1; dl <= 1 && is_max; dl++) {
                for (int dy = -1; dy <= 1 && is_max; dy++) {
                    for (int dx = -1; dx <= 1 && is_max; dx++) {
                        if (dl == 0 && dy == 0 && dx == 0) {
                            before = false;
                            continue;
                        }
                        const double n = R(dl, dy, dx);
                        is_max = before ? c > n : c >= n;
                    }
                }
            }
            if (!is_max) continue;
            // Maximum of the quadratic through the neighbourhood (Brown & Lowe 2002), in units
            // of samples (x, y) and layers (scale).
            const Eigen::Vector3d g(0.5 * (R(0, 0, 1) - R(0, 0, -1)),
                                    0.5 * (R(0, 1, 0) - R(0, -1, 0)),
                                    0.5 * (R(1, 0, 0) - R(-1, 0, 0)));
            Eigen::Matrix3d H;
            H(0, 0) = R(0, 0, 1) + R(0, 0, -1) - 2 * c;
            H(1, 1) = R(0, 1, 0) + R(0, -1, 0) - 2 * c;
            H(2, 2) = R(1, 0, 0) + R(-1, 0, 0) - 2 * c;
            H(0, 1) = H(1, 0) = 0.25 * (R(0, 1, 1) - R(0, 1, -1) - R(0, -1, 1) + R(0, -1, -1));
            H(0, 2) = H(2, 0) = 0.25 * (R(1, 0, 1) - R(1, 0, -1) - R(-1, 0, 1) + R(-1, 0, -1));
            H(1, 2) = H(2, 1) = 0.25 * (R(1, 1, 0) - R(1, -1, 0) - R(-1, 1, 0) + R(-1, -1, 0));
            const Eigen::FullPivLU<Eigen::Matrix3d> lu(H);
            if (!lu.isInvertible()) continue;
            const Eigen::Vector3d offset = -lu.solve(g);
            if (!(offset.cwiseAbs().maxCoeff() <= 1.0)) continue;
            const int size = v[1].layer->filter_size;
            const int size_step = v[2].layer->filter_size - size;
            FastHessianDetector::TKeypoint kp;
            kp.x = (gx + offset.x()) * step;
            kp.y = (gy + offset.y()) * step;
            kp.scale = FastHessianDetector::scaleOfFilterSize(size + offset.z() * size_step);
            kp.response = c + 0.5 * g.dot(offset);
            kp.laplacian_sign = v[1].layer->laplacian_positive[v[1].index(gx, gy)] ? 1 : -1;
            out.push_back(kp);
        }
    }
}

}  // namespace

void FastHessianDetector::TOptions::validate() const
{
    constexpr const char* kOwner = "FastHessianDetector";
    requireParameter(std::isfinite(hessian_threshold) && hessian_threshold >= 0, kOwner,
                     "hessian_threshold", hessian_threshold, "must be >= 0");
    requireParameter(octaves >= 1 && octaves <= 8, kOwner, "octaves", octaves, "must be in [1, 8]");
    requireParameter(initial_step >= 1, kOwner, "initial_step", initial_step, "must be >= 1");
}

void FastHessianDetector::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                       const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(hessian_threshold, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(octaves, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(initial_step, int, cfg, section);
    validate();
}

void FastHessianDetector::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                                     const std::string& s) const
{
    MRPT_SAVE_CONFIG_VAR_COMMENT(hessian_threshold, "[gray levels^2] minimum det(H) of a keypoint");
    MRPT_SAVE_CONFIG_VAR_COMMENT(octaves, "number of octaves (filter sizes 9-27, 15-51, ...)");
    MRPT_SAVE_CONFIG_VAR_COMMENT(initial_step, "[px] sampling step of the first octave");
}

FastHessianDetector::FastHessianDetector() : FastHessianDetector(TOptions()) {}

FastHessianDetector::FastHessianDetector(const TOptions& options) : m_options(options)
{
    m_options.validate();
}

int FastHessianDetector::filterSize(int octave, int layer)
{
    // Sec. 3.3: sizes grow by 6, 12, 24, ... within octaves 0, 1, 2, ...
    return 3 * ((2 << octave) * (layer + 1) + 1);
}

FastHessianDetector::THessian FastHessianDetector::boxHessian(const IntegralImage& ii, int col,
                                                              int row, int filter_size)
{
    return boxResponses(ii, col, row, TBoxFilter(filter_size));
}

std::vector<FastHessianDetector::TKeypoint> FastHessianDetector::detect(const IntegralImage& ii,
                                                                        unsigned threads) const
{
    const int width = ii.width(), height = ii.height();
    // Response maps by filter size; a size shared with a finer octave keeps its finer grid.
    std::map<int, TResponseLayer> layers;
    std::vector<TKeypoint> keypoints;
    for (int octave = 0; octave < m_options.octaves; octave++) {
        const int step = m_options.initial_step << octave;
        // A candidate of layer i needs the filter of layer i + 1 at ±1 sample inside the image;
        // none fits from here on.
        if (filterSize(octave, 2) + 2 * step > std::min(width, height)) break;
        std::vector<TOctaveView> views;
        for (int i = 0; i < kLayersPerOctave; i++) {
            const int size = filterSize(octave, i);
            auto it = layers.find(size);
            if (it == layers.end())
                it = layers.emplace(size, computeLayer(ii, size, step, threads)).first;
            views.emplace_back(it->second, step);
        }
        // The two middle layers of the octave (Sec. 3.4).
        for (int i = 1; i + 1 < kLayersPerOctave; i++) {
            findMaxima({views[i - 1], views[i], views[i + 1]}, step, width, height,
                       m_options.hessian_threshold, keypoints);
        }
    }
    return keypoints;
}

}  // namespace mrpt_vslam::core
