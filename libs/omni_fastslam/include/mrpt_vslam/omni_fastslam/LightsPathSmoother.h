#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/core/SensorPoseCorrection.h>
#include <mrpt_vslam/omni_fastslam/COmniFastSLAM.h>

#include <optional>
#include <utility>
#include <vector>

namespace mrpt_vslam::omni_fastslam {

/** The most probable path and lights after a run (ours; doc/omni-fastslam.md §9): given every
 *  odometry increment and every bearing the best particle associated with a light of its map,
 *  least squares over the whole path and the lights (Levenberg-Marquardt on the odometry
 *  Gaussians and the bearings' Q, Huber on the bearings), the start pose fixed. A light nearer
 *  than the map's nearest reading range (sensorLimitsInUse()) to a camera that reads it costs
 *  ((range − that) / 1 cm)² per bearing: no reading comes from nearer. FastSLAM with few particles
 * keeps one path hypothesis where the loop closes, so the error of the odometry before the loop
 * stays in its map; the least squares spread it along the path.
 *
 *  Then, with options.merge_distance > 0, two lights closer than that which no frame measured
 *  together become one (a light mapped twice) and the least squares run again.
 *
 *  Usage: `filter.setStepObserver(&smoother);` before `filter.reset()`, run the filter, then
 *  `smoother.smooth(filter.bestParticle())`. */
class LightsPathSmoother : public COmniFastSLAM::TStepObserver {
  public:
    /// Options (ini section `[LightsPathSmoother]` in omni-fastslam).
    struct TOptions : public mrpt::config::CLoadableOptions {
        /// The smoothed path and lights are the run's result (the filter's are kept beside).
        bool smooth_path = true;
        unsigned int max_iterations = 50;  ///< per least-squares solution
        /// Solutions: the first with the particle's associations, each next one with the
        /// bearings associated again at the poses of the one before.
        unsigned int rounds = 2;
        double huber = 3;           ///< Huber threshold of the bearings [σ] (0: none)
        double merge_distance = 0;  ///< [m]; 0: no merging

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
    } options;

    void onReset(const mrpt::math::TPose2D& robot_in_map, double timestamp) override;
    void onStep(const core::TOdometryGaussian& motion,
                const std::vector<TBearingMeasurement>& z) override;

    struct TResult {
        std::vector<std::pair<double, mrpt::math::TPose2D>> path;  ///< oldest first
        /// The particle's map with the smoothed lights (candidates dropped).
        CCeilingLightsMap map;
        size_t iterations = 0;
        size_t bearings = 0;  ///< bearing terms
        size_t outliers = 0;  ///< bearings beyond the Huber threshold at the end
        /// The probability of a bearing beyond the Huber threshold with the noise and camera
        /// right: the χ² tail of its dimension (1 planar, 2 spatial); 0 without Huber.
        double outlier_probability = 0;
        size_t merged = 0;  ///< lights merged into another
        /// lights whose least-squares covariance is not positive definite: the map keeps the
        /// filter's
        size_t lights_with_filter_covariance = 0;
        double initial_cost = 0, final_cost = 0;  ///< Σ of the squared whitened residuals
    };
    /** Smooths particle `p`'s path and the lights of its map it associated measurements with.
     *  \pre registered with the filter before its reset()
     *  \throw std::logic_error if `p`'s path does not hold the start and one step per recorded step
     */
    TResult smooth(const TOmniFastSLAMParticle& p) const;

    /** The correction of the camera's pose on the robot that best explains the bearings
     *  particle `p` associated with a light of its map (core::TSensorPoseCorrection): each
     *  bearing read as the point where its ray meets the plane of its light's height, paired
     *  with the bearing of the same light up to 3 steps before, through the odometry between
     *  them. None with the planar model (an azimuth meets no plane) or without pairs.
     *  \pre registered with the filter before its reset() */
    std::optional<core::TSensorPoseCorrection> cameraPoseCheck(
        const TOmniFastSLAMParticle& p) const;

  private:
    struct TStep {
        core::TOdometryGaussian motion;
        std::vector<TBearingMeasurement> z;
    };
    std::vector<TStep> m_steps;
    /// `p`'s steps, oldest first: the start and one per recorded step.
    /// \throw std::logic_error if they are not
    std::vector<const TOmniFastSLAMPath::TStep*> recordedStepsOf(
        const TOmniFastSLAMParticle& p) const;
};

}  // namespace mrpt_vslam::omni_fastslam
