#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <memory>
#include <optional>
#include <string>

namespace mrpt::img {
class CImage;
}

namespace mrpt_vslam::multirobot {

/** A disparity found by StereoMatcher::match(). */
struct TStereoMatch {
    double disparity = 0;  ///< d = c_left − c_right [px], sub-pixel
    double ncc = 0;        ///< normalized cross-correlation at the best integer disparity
};

/** Stereo correspondence of single left pixels on a rectified pair (Gil et al. 2010, Sec. 6.1:
 *  "the stereo correspondence is found in the stereo images"; the paper does not say how):
 *
 *   1. Take the w × w patch around the left pixel (r, c).
 *   2. Along the same row of the right image, score every column c − d, d ∈ [d_min, d_max],
 *      with the normalized cross-correlation (NCC) of the two patches, which ignores gain and
 *      offset changes between the cameras. Right-image patch sums come from integral images,
 *      so each candidate costs one w²-term dot product.
 *   3. The best score must be at least `min_ncc`, must not lie on either end of the searched
 *      range (the true peak could be outside), and must be unique: with the distance of two
 *      normalised patches δ = √(2(1 − NCC)), δ_best < uniqueness_ratio · δ_second, where the
 *      second is the best other local maximum of the score along the row (Lowe's ratio test
 *      applied to patches; repetitive texture fails it).
 *   4. Sub-pixel disparity: vertex of the parabola through the scores at d_best − 1, d_best,
 *      d_best + 1.
 *   5. Optionally (left_right_check), search back from the right patch along the left row;
 *      the best integer disparity must agree within 1 px.
 *
 *  Usage: `StereoMatcher m(left_gray, right_gray, options);` once per frame, then
 *  `if (auto s = m.match(row, col)) ...` per left pixel.
 */
class StereoMatcher {
  public:
    /** Keys of the `[StereoFrontEnd]` section read by this class (the paper gives none). */
    struct TOptions : public mrpt::config::CLoadableOptions {
        int min_disparity = 1;          ///< [px] smallest disparity searched (≥ 1)
        int max_disparity = 128;        ///< [px] largest disparity searched
        int ncc_window = 11;            ///< [px] side w of the correlation patch (odd, 3-51)
        double min_ncc = 0.9;           ///< minimum NCC of an accepted match, in (−1, 1]
        double uniqueness_ratio = 0.8;  ///< δ_best < ratio · δ_second, in (0, 1]
        bool left_right_check = true;   ///< search back from the right image (step 5)

        /** Reads and validates the keys; throws std::invalid_argument with a one-line message
         *  naming the section and key. */
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
        /** Throws std::invalid_argument naming `section` and the first invalid key. */
        void validate(const std::string& section) const;
    };

    /** Prepares the integral images of a rectified pair of 8-bit grayscale images of equal
     *  size. \throw std::invalid_argument otherwise, or if the options are invalid. */
    StereoMatcher(const mrpt::img::CImage& left, const mrpt::img::CImage& right,
                  const TOptions& options);
    ~StereoMatcher();
    StereoMatcher(const StereoMatcher&) = delete;
    StereoMatcher& operator=(const StereoMatcher&) = delete;

    /** Steps 1–5 for the left pixel at row `row`, column `col`, with the searched disparities
     *  moved by `column_offset` [px] (d ∈ [d_min + offset, d_max + offset]: the right image's
     *  columns offset by a rectification, StereoGeometry::disparityOffset() rounded).
     *  \return std::nullopt when the patch leaves the image, the left patch is flat, or a test
     *  fails. */
    std::optional<TStereoMatch> match(int row, int col, int column_offset = 0) const;

    /** Pixels from the border that the left patch needs: w / 2. */
    int halfWindow() const { return m_options.ncc_window / 2; }

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
    TOptions m_options;
};

}  // namespace mrpt_vslam::multirobot
