#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt_vslam/viewmap/PlanarEssentialMatrix.h>

#include <optional>
#include <vector>

namespace mrpt::random {
class CRandomGenerator;
}

namespace mrpt_vslam::viewmap {

/** Robust estimate of the observation (φ, β) of a stored view from matched unit rays
 *  (doc/core-features.md §4, step 4 of doc/view-slam.md §4):
 *
 *   1. RANSAC (Fischler & Bolles 1981) over minimal samples of 4 matches, each solved with
 *      PlanarEssentialMatrix::fit(); degenerate samples are skipped.
 *   2. Each hypothesis is scored with the truncated quadratic cost Σ min(r², τ²) of MSAC (Torr &
 *      Zisserman 2000), r the Sampson residual on the sphere (PlanarEssentialMatrix::residual)
 *      and τ the inlier threshold. Its inliers are the matches with r ≤ τ whose depths are not
 *      negative for the direction of translation most of them agree on (cheirality):
 *      wrong matches that happen to lie near their epipolar plane but behind the cameras drop
 *      out.
 *   3. Every new best hypothesis is refitted on its inliers while that lowers the cost (local
 *      optimisation, Chum, Matas & Kittler 2003): 4-match samples are noisy, so this is what
 *      turns a good sample into the best model. The final model is this refit on all inliers.
 *   4. The number of samples adapts to the best inlier ratio w:
 *      N = log(1 − confidence) / log(1 − w⁴), at most max_iterations.
 *   5. φ or φ + π by cheirality over the inliers.
 *
 *  No solution (nullopt) when fewer than min_inliers matches agree, when cheirality cannot
 *  decide, or when the median parallax of the inliers, the angle between p_v and R_z(β) p_l, is
 *  below min_parallax: then a rotation alone explains the rays and the bearing φ is not
 *  observable (zero or tiny baseline, or all points far away). Pure noise gives a median
 *  parallax of about 1.7 times the angular noise of one ray, so min_parallax must stay above
 *  twice that noise.
 *
 *  Usage: `auto r = PlanarEssentialRansac(opts).estimate(rays_v, rays_l, rng); if (r) ...`
 */
class PlanarEssentialRansac {
  public:
    /// Parameters; ini keys are the member names, angles in degrees with `_deg`.
    struct TOptions : public mrpt::config::CLoadableOptions {
        double inlier_threshold = 0.017453292519943295;  ///< [rad] τ (`inlier_threshold_deg`, 1°)
        double confidence = 0.99;  ///< probability of drawing one outlier-free sample
        int max_iterations = 1000;
        int min_inliers = 8;
        double min_parallax = 0.017453292519943295;  ///< [rad] (`min_parallax_deg`, 1°)

        /// Throws std::invalid_argument naming the ini key of a bad value.
        void validate() const;
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
    };

    /// A robust estimate.
    struct TResult {
        TViewObservation observation;     ///< (φ, β) [rad]
        PlanarEssentialMatrix essential;  ///< refitted on the inliers
        std::vector<bool> inliers;        ///< per match
        size_t inlier_count = 0;
        double rms_residual = 0;     ///< [rad] RMS Sampson residual over the inliers
        double median_parallax = 0;  ///< [rad] median angle between p_v and R_z(β) p_l
        size_t iterations = 0;       ///< RANSAC samples drawn
    };

    /// Estimator with the default options.
    PlanarEssentialRansac();
    /// \throw std::invalid_argument if the options are invalid (TOptions::validate()).
    explicit PlanarEssentialRansac(const TOptions& options);

    /** Robust (φ, β) from the matches (column k of both 3 × n matrices: unit rays of match k in
     *  the robot frame and in the view). Samples are drawn from `rng`, so a seeded generator
     *  gives reproducible results.
     *  \return nullopt when there is no reliable solution (see the class notes).
     *  \throw std::invalid_argument for rays of different counts or not of unit length. */
    std::optional<TResult> estimate(const Eigen::Matrix3Xd& rays_v, const Eigen::Matrix3Xd& rays_l,
                                    mrpt::random::CRandomGenerator& rng) const;

    const TOptions& options() const { return m_options; }

  private:
    TOptions m_options;
};

}  // namespace mrpt_vslam::viewmap
