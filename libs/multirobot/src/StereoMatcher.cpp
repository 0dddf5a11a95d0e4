#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/img/CImage.h>
#include <mrpt_vslam/core/ConfigSectionWriter.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/multirobot/StereoMatcher.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

namespace mrpt_vslam::multirobot {

void StereoMatcher::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                 const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(min_disparity, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(max_disparity, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(ncc_window, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(min_ncc, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(uniqueness_ratio, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(left_right_check, bool, cfg, section);
    validate(section);
}

void StereoMatcher::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                               const std::string& section) const
{
    const core::ConfigSectionWriter put(cfg, section);
    put("min_disparity", min_disparity, "[px] smallest disparity searched (>= 1)");
    put("max_disparity", max_disparity, "[px] largest disparity searched");
    put("ncc_window", ncc_window, "[px] side of the correlation patch (odd, 3 to 51)");
    put("min_ncc", min_ncc, "minimum normalized cross-correlation of a match");
    put("uniqueness_ratio", uniqueness_ratio, "best vs second peak patch-distance ratio");
    put("left_right_check", left_right_check, "search back from the right image");
}

void StereoMatcher::TOptions::validate(const std::string& section) const
{
    using core::requireKey;
    requireKey(min_disparity >= 1, section, "min_disparity", "must be >= 1");
    requireKey(max_disparity >= min_disparity + 2, section, "max_disparity",
               "must be >= min_disparity + 2 (a peak needs two neighbours)");
    requireKey(ncc_window >= 3 && ncc_window <= 51 && ncc_window % 2 == 1, section, "ncc_window",
               "must be odd, from 3 to 51");
    requireKey(min_ncc > -1 && min_ncc <= 1, section, "min_ncc", "must be in (-1, 1]");
    requireKey(uniqueness_ratio > 0 && uniqueness_ratio <= 1, section, "uniqueness_ratio",
               "must be in (0, 1]");
}

namespace {

/** Integral images of an 8-bit image: sums and sums of squares over any box. */
struct TIntegral {
    cv::Mat sum, sqsum;  ///< (H+1) × (W+1), CV_64F

    explicit TIntegral(const cv::Mat& img) { cv::integral(img, sum, sqsum, CV_64F, CV_64F); }

    static double box(const cv::Mat& t, int r0, int c0, int r1, int c1)
    {
        return t.at<double>(r1, c1) - t.at<double>(r0, c1) - t.at<double>(r1, c0) +
               t.at<double>(r0, c0);
    }
};

/** NCC scores of a template patch against the patches of one row of another image. */
struct TRowScores {
    int first_d = 0;          ///< disparity of scores[0]
    std::vector<double> ncc;  ///< one per disparity, contiguous

    /// Index of the highest score.
    size_t best() const
    {
        return static_cast<size_t>(std::max_element(ncc.begin(), ncc.end()) - ncc.begin());
    }
};

cv::Mat gray8(const mrpt::img::CImage& img, const char* which)
{
    if (img.isEmpty() || img.getWidth() == 0 || img.getHeight() == 0)
        throw std::invalid_argument(std::string(which) + " image is empty");
    if (img.isColor() || img.getPixelDepth() != mrpt::img::PixelDepth::D8U)
        throw std::invalid_argument(std::string(which) + " image must be 8-bit grayscale");
    return img.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
}

}  // namespace

struct StereoMatcher::Impl {
    cv::Mat left, right;
    TIntegral left_integral, right_integral;
    int half = 0;

    Impl(const cv::Mat& l, const cv::Mat& r, int half_window)
        : left(l), right(r), left_integral(l), right_integral(r), half(half_window)
    {
    }

    /** Scores of the patch of `tmpl` at (row, col) against the patches of `search` at
     *  columns col + sign·d, d = d_min..d_max, as far as they stay inside the image.
     *  Empty when the template is flat. */
    TRowScores scores(const cv::Mat& tmpl, const cv::Mat& search, const TIntegral& integral,
                      int row, int col, int sign, int d_min, int d_max) const
    {
        const int w = 2 * half + 1;
        const double n = w * w;
        // Σ t'·R with t' = t − mean t equals Σ t·R − (Σ t)(Σ R)/n: integer dot products only.
        std::vector<int32_t> t(static_cast<size_t>(w * w));
        int64_t sum_t = 0, sum_tt = 0;
        for (int y = 0; y < w; y++) {
            const uint8_t* p = tmpl.ptr<uint8_t>(row - half + y) + (col - half);
            for (int x = 0; x < w; x++) {
                t[y * w + x] = p[x];
                sum_t += p[x];
                sum_tt += p[x] * p[x];
            }
        }
        const double s_tt = static_cast<double>(sum_tt) - static_cast<double>(sum_t) * sum_t / n;
        TRowScores out;
        if (s_tt <= 1e-9) return out;

        // Column of the search patch centre must keep the patch inside the image.
        const int d_lo =
            sign < 0 ? std::max(d_min, col + half + 1 - search.cols) : std::max(d_min, half - col);
        const int d_hi =
            sign < 0 ? std::min(d_max, col - half) : std::min(d_max, search.cols - 1 - half - col);
        out.first_d = d_lo;
        for (int d = d_lo; d <= d_hi; d++) {
            const int c = col + sign * d;
            const int r0 = row - half, c0 = c - half;
            const double s = TIntegral::box(integral.sum, r0, c0, r0 + w, c0 + w);
            const double s2 = TIntegral::box(integral.sqsum, r0, c0, r0 + w, c0 + w);
            const double s_rr = s2 - s * s / n;
            int32_t dot = 0;
            for (int y = 0; y < w; y++) {
                const uint8_t* p = search.ptr<uint8_t>(r0 + y) + c0;
                const int32_t* q = &t[y * w];
                for (int x = 0; x < w; x++) dot += q[x] * p[x];
            }
            const double s_tr = dot - static_cast<double>(sum_t) * s / n;
            out.ncc.push_back(s_rr > 1e-9 ? s_tr / std::sqrt(s_tt * s_rr) : 0.0);
        }
        return out;
    }
};

StereoMatcher::StereoMatcher(const mrpt::img::CImage& left, const mrpt::img::CImage& right,
                             const TOptions& options)
    : m_options(options)
{
    m_options.validate("StereoFrontEnd");
    const cv::Mat l = gray8(left, "left"), r = gray8(right, "right");
    if (l.size() != r.size())
        throw std::invalid_argument("left and right images differ in size (" +
                                    std::to_string(l.cols) + "x" + std::to_string(l.rows) + " vs " +
                                    std::to_string(r.cols) + "x" + std::to_string(r.rows) + ")");
    m_impl = std::make_unique<Impl>(l, r, halfWindow());
}

StereoMatcher::~StereoMatcher() = default;

std::optional<TStereoMatch> StereoMatcher::match(int row, int col, int column_offset) const
{
    const Impl& m = *m_impl;
    const int h = m.half;
    if (row < h || col < h || row + h >= m.left.rows || col + h >= m.left.cols) return std::nullopt;

    // Steps 1-2: scores along the right row, right column = col − d
    const int d_min = m_options.min_disparity + column_offset;
    const int d_max = m_options.max_disparity + column_offset;
    const TRowScores s = m.scores(m.left, m.right, m.right_integral, row, col, -1, d_min, d_max);
    if (s.ncc.size() < 3) return std::nullopt;
    const size_t b = s.best();
    const double best = s.ncc[b];

    // Step 3: threshold, peak inside the range, uniqueness against the other local maxima
    if (best < m_options.min_ncc || b == 0 || b + 1 == s.ncc.size()) return std::nullopt;
    double second = -1;
    for (size_t j = 0; j < s.ncc.size(); j++) {
        if (j == b) continue;
        const bool rises = j == 0 || s.ncc[j] >= s.ncc[j - 1];
        const bool falls = j + 1 == s.ncc.size() || s.ncc[j] >= s.ncc[j + 1];
        if (rises && falls) second = std::max(second, s.ncc[j]);
    }
    const auto patch_distance = [](double ncc) { return std::sqrt(std::max(0.0, 2 * (1 - ncc))); };
    if (second > -1 &&
        !(patch_distance(best) < m_options.uniqueness_ratio * patch_distance(second)))
        return std::nullopt;

    // Step 4: parabola vertex through the best score and its two neighbours
    const double a = s.ncc[b - 1], c = s.ncc[b + 1];
    const double curvature = a - 2 * best + c;
    const double offset = curvature < 0 ? 0.5 * (a - c) / curvature : 0.0;
    const int d_best = s.first_d + static_cast<int>(b);

    // Step 5: the right patch must find its way back to the same left column (±1 px)
    if (m_options.left_right_check) {
        const int col_right = col - d_best;
        const TRowScores back =
            m.scores(m.right, m.left, m.left_integral, row, col_right, +1, d_min, d_max);
        if (back.ncc.empty() || std::abs(back.first_d + static_cast<int>(back.best()) - d_best) > 1)
            return std::nullopt;
    }
    return TStereoMatch{d_best + offset, best};
}

}  // namespace mrpt_vslam::multirobot
