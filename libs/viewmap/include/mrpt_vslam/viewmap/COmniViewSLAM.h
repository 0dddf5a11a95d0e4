#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/viewmap/CViewMap.h>
#include <mrpt_vslam/viewmap/OmniFeatureExtractor.h>
#include <mrpt_vslam/viewmap/OmniViewObserver.h>
#include <mrpt_vslam/viewmap/ViewInitializationPolicy.h>
#include <mrpt_vslam/viewmap/ViewMapEKF.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mrpt::img {
class CImage;
}

namespace mrpt_vslam::viewmap {

/** View-based omnidirectional EKF SLAM (Valiente et al. 2015; doc/view-slam.md §4, one pass per
 *  image):
 *
 *   1. predict the robot pose with the odometry increment and its covariance;
 *   2. extract the feature points of the omni image (OmniFeatureExtractor);
 *   3. candidate views: the nearest ones within candidate_distance of the estimated robot
 *      position, not closer than min_baseline (φ is undefined on the view), at most
 *      max_candidates;
 *   4. for each, match in the uncertainty-driven area and estimate z = (φ, β) and R with the
 *      planar essential matrix (OmniViewObserver), then the χ²-gated EKF update,
 *      nearest view first;
 *   5. the view-initialization policy decides whether to start a view at the robot pose
 *      (ViewInitializationPolicy); the view keeps this image's points.
 *  The view map (CViewMap) mirrors the EKF: syncMap() copies the estimates into it.
 *
 *  Usage: `COmniViewSLAM slam(opts, extractor, observer_opts, policy_opts, seed);`
 *  `slam.reset(start);` then `slam.processStep(u, Q, image, t, file)` per frame.
 */
class COmniViewSLAM {
  public:
    /// Filter parameters (ini section [ViewSLAM]).
    struct TOptions : public mrpt::config::CLoadableOptions {
        double candidate_distance = 3.0;  ///< [m] views farther than this are not tried
        int max_candidates = 3;           ///< views tried per step, nearest first
        /// [m] views nearer than this are not observed (nearer ones gave several times larger
        /// bearing errors, doc/view-slam.md)
        double min_baseline = 0.3;
        double gate_probability = 0.99;                   ///< χ²₂ gate of the EKF update
        double initial_sigma_xy = 0.01;                   ///< [m] P0 of the start pose
        double initial_sigma_yaw = 0.008726646259971648;  ///< [rad] (initial_sigma_yaw_deg)

        /// Throws std::invalid_argument naming the key of a bad value.
        void validate() const;
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
    };

    /// One observation attempted in a step.
    struct TObservationRecord {
        size_t view = 0;
        size_t matches = 0, inliers = 0;
        bool estimated = false;  ///< RANSAC found (φ, β)
        bool accepted = false;   ///< and the EKF gate let it in
        TViewObservation z;
        Eigen::Matrix2d R = Eigen::Matrix2d::Zero();
        double nis = 0;
    };

    /// What a step did.
    struct TStepResult {
        size_t features = 0;
        std::vector<TObservationRecord> observations;
        TViewDecision decision;
        std::optional<size_t> new_view;  ///< index of the view started, if any
        size_t accepted() const;
    };

    /// \throw std::invalid_argument for invalid options.
    COmniViewSLAM(const TOptions& options, OmniFeatureExtractor extractor,
                  const OmniViewObserver::TOptions& observer,
                  const ViewInitializationPolicy::TOptions& policy, uint32_t seed);

    /** The filter of an `.ini` (doc/view-slam.md, "Parameters"): [ViewSLAM] (TOptions), [Camera]
     *  (core::UnifiedSphereCamera), [CameraOnRobot] (x, y [m], yaw_deg, pitch_deg, roll_deg: when
     *  any is given, the camera's pose for every image, absent ones 0; else each image's own,
     *  see useCameraPoseOf()), [Features], [ViewObserver] and [ViewInitialization]; keys absent
     *  from [Features] and [ViewObserver] take the filter's values (filterFeatureOptions(),
     *  filterObserverOptions()).
     *  \throw std::invalid_argument naming the section and key of a bad value. */
    static std::unique_ptr<COmniViewSLAM> fromConfig(const mrpt::config::CConfigFileBase& cfg,
                                                     uint32_t seed);

    /** The front-end options recommended inside the filter, where they differ from the
     *  front-end classes' own defaults (measured one image pair at a time): inside the filter an
     *  observation's errors repeat frame after frame, so the detector keeps fewer, stronger
     *  points (det(H) ≥ 30), matches may be farther apart (descriptor distance 0.6), an
     *  observation needs 20 inliers, and R is floored at 1.5° in φ and 0.75° in β for a
     *  consistent NEES (doc/view-slam.md, "Parameters"). */
    static OmniFeatureExtractor::TOptions filterFeatureOptions();
    static OmniViewObserver::TOptions filterObserverOptions();

    /// Empties the map and puts the robot at `start` with P0 (clears everything).
    void reset(const mrpt::math::TPose2D& start);

    /** One frame: steps 1-5 above. `increment` is the odometry since the previous frame in the
     *  robot frame, Q its covariance; without an image (nullptr) only step 1. `timestamp` [s]
     *  and `image_file` are stored with a new view.
     *  \throw std::invalid_argument for a non-finite increment or a bad image. */
    TStepResult processStep(const mrpt::math::TPose2D& increment, const Eigen::Matrix3d& Q,
                            const mrpt::img::CImage* image, double timestamp,
                            const std::string& image_file = {});

    /** The camera's pose on the robot for the next images: that of `camera_on_robot` (an
     *  image's own `cameraPose`) unless the config's [CameraOnRobot] set it. Its rotation
     *  turns the image's bearings into the robot frame, its horizontal position is where the
     *  observations are made from (ViewMapEKF::setCameraPosition()); its height plays no
     *  part. */
    void useCameraPoseOf(const mrpt::poses::CPose3D& camera_on_robot);
    /** The camera model of the next images in place of [Camera]'s: an image's own calibration
     *  fitted (core::fitUnifiedSphere()). \throw std::invalid_argument if it is not valid. */
    void setCamera(const core::UnifiedSphereCamera& camera) { m_extractor.setCamera(camera); }
    /// Whether the config's [CameraOnRobot] sets the camera's pose.
    bool cameraOnRobotConfigured() const { return m_camera_on_robot_configured; }
    /// [m] The camera's horizontal position on the robot in use.
    const mrpt::math::TPoint2D& cameraPosition() const { return m_ekf.cameraPosition(); }
    const OmniFeatureExtractor& extractor() const { return m_extractor; }
    const OmniViewObserver& observer() const { return m_observer; }
    /// Threads the feature extraction runs on (0: every core; default 1); the results do not
    /// depend on it.
    void setThreadCount(unsigned threads) { m_extractor.setThreadCount(threads); }

    const ViewMapEKF& ekf() const { return m_ekf; }
    /// The view map with the EKF's current estimates.
    const CViewMap& map();
    const TOptions& options() const { return m_options; }

  private:
    /// Candidate views of step 3, nearest first.
    std::vector<size_t> candidateViews() const;

    TOptions m_options;
    OmniFeatureExtractor m_extractor;
    OmniViewObserver m_observer;
    ViewInitializationPolicy::TOptions m_policy_options;
    std::unique_ptr<ViewInitializationPolicy> m_policy;
    mrpt::random::CRandomGenerator m_rng;
    uint32_t m_seed;
    ViewMapEKF m_ekf;
    CViewMap m_map;
    double m_gate = 0;
    bool m_camera_on_robot_configured = false;
};

}  // namespace mrpt_vslam::viewmap
