#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt_vslam/core/GaussianProcessRegression.h>

#include <Eigen/Core>
#include <vector>

namespace mrpt::random {
class CRandomGenerator;
}

namespace mrpt_vslam::viewmap {

/** Existence probability of the current image's feature points, learnt by Gaussian-process
 *  regression (Valiente et al. 2015, abstract: "a Gaussian Process to infer an information
 *  distribution model from sensor data. This model represents feature points existence
 *  probabilities").
 *
 *  [ours, doc/view-slam.md §4.2] The inputs are the points' unit rays in the robot frame (the
 *  chord between two rays is their angular distance, to first order); the target of a point is
 *  1 when it is an inlier of an accepted view observation (it exists in the map's views and is
 *  consistent with them) and 0 otherwise. The prior mean is the share of such points; the
 *  squared-exponential kernel's hyperparameters are fitted by marginal likelihood
 *  (core::GaussianProcessRegression), refitted every `refit_every` calls from the previous ones.
 *  The model is then read at the points themselves (a smoothed, uncertainty-aware count):
 *
 *      p(d) = clamp(m + μ(d), 0, 1),   p⁻(d) = clamp(m + μ(d) − κ σ(d), 0, 1)
 *
 *  and its information content is summarised by n⁻ = Σ_k p⁻(d_k), the number of points that
 *  surely exist in the map's views: isolated matches (high σ) and matches among unmatched
 *  neighbours (low μ) count less than a consistent region of the image.
 */
class FeatureExistenceModel {
  public:
    /// Parameters (ini keys = member names).
    struct TOptions : public mrpt::config::CLoadableOptions {
        int max_points = 120;  ///< points used for the fit (a seeded random subset beyond)
        int refit_every = 10;  ///< hyperparameters refitted every this many fits (1: always)
        double confidence_sigmas = 1.0;  ///< κ of the lower bound p⁻

        /// Throws std::invalid_argument naming the key of a bad value.
        void validate() const;
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
    };

    /// What one fit says.
    struct TContent {
        double existence = 0;        ///< mean of p over the points used
        double lower_existence = 0;  ///< mean of p⁻ over the points used
        double prior_mean = 0;       ///< m: share of consistent points used
        size_t points = 0;           ///< points used
        core::GaussianProcessRegression::THyperParameters hyper;
        /// n⁻ scaled to all the image's points: lower_existence × (number of points).
        double sure_points = 0;
    };

    /// Model with the default options.
    FeatureExistenceModel();
    /// \throw std::invalid_argument if the options are invalid.
    explicit FeatureExistenceModel(const TOptions& options);

    /** Fits the model to the points (column k of `rays` with target `consistent[k]`) and
     *  returns its content. Fewer than 3 points: nothing is learnt and the content is 0.
     *  \throw std::invalid_argument if the sizes differ. */
    TContent fit(const Eigen::Matrix3Xd& rays, const std::vector<bool>& consistent,
                 mrpt::random::CRandomGenerator& rng);

    /// The fitted regression (zero-mean targets y − m).
    const core::GaussianProcessRegression& regression() const { return m_gp; }

  private:
    TOptions m_options;
    core::GaussianProcessRegression m_gp;
    int m_fits = 0;
};

}  // namespace mrpt_vslam::viewmap
