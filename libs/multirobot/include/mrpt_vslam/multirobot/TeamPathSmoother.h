#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/core/SensorHeightOffset.h>
#include <mrpt_vslam/core/SensorPoseCorrection.h>
#include <mrpt_vslam/core/SensorTiltCorrection.h>
#include <mrpt_vslam/multirobot/CMultiRobotVisualSLAM.h>
#include <mrpt_vslam/multirobot/CVisualLandmarksMap.h>
#include <mrpt_vslam/multirobot/PlanarPoseLandmarkGraph.h>
#include <mrpt_vslam/multirobot/TeamParticle.h>

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mrpt_vslam::multirobot {

/** What is made after the filter, along the best particle's path (ours; doc/multirobot.md §3):
 *  the map of every measurement made again along the path (mapAlongPath()), the most
 *  probable paths given every odometry increment and reading (smoothPaths()) and the check of
 *  the sensors' poses on the robots (sensorPoseChecks()).
 *
 *  It records the run as CMultiRobotVisualSLAM's step observer: each robot's odometry
 *  Gaussian, measurements and readings of other robots, step by step, and the start poses.
 *  Usage: `TeamPathSmoother smoother(map_template); smoother.options = ...;
 *  filter.setStepObserver(&smoother);` before `filter.reset()`, run the filter, then
 *  `smoother.smoothPaths(filter.bestParticle())`, `smoother.mapAlongPath(...)` or
 *  `smoother.sensorPoseChecks(...)`. */
class TeamPathSmoother : public CMultiRobotVisualSLAM::TStepObserver {
  public:
    /// Options (ini section `[TeamPathSmoother]` in multirobot-vslam).
    struct TOptions : public mrpt::config::CLoadableOptions {
        /// The output map is the map along the best particle's path (mapAlongPath()).
        bool map_along_path = false;
        /// Mapping along a path: D0 of its gate, and the fewest measurements a landmark of it
        /// needs as a fraction of the recorded frames with landmark measurements, in [0, 1]
        /// (a landmark takes at most one measurement per frame; minTimesSeen()).
        double D0 = 30;
        double min_seen_fraction = 0;
        /// Mapping along a path, the points of a frame take distinct landmarks: false, in the
        /// order of the points (the nearest first, as the filter takes them); true, nearest
        /// pair first (CVisualLandmarksMap::associateNearestFirst()). True made fewer
        /// duplicates on the simulated range-bearing rawlogs, false smaller errors on MRCLAM
        /// (doc/multirobot.md §3).
        bool nearest_pair_first = false;
        /// smoothPaths() as the result (needs map_along_path): rounds of mapping along the
        /// path and least squares, and the Huber threshold [σ] of its readings (0: none).
        bool smooth_paths = false;
        unsigned int rounds = 2;
        double huber = 3;
        /// smoothPaths(): σ of the prior N(1, σ²) on each robot's odometry scales (distance,
        /// turn; 0: no scales), and the factor on the odometry covariance.
        double odometry_scale_std = 0;
        double motion_cov_factor = 1;
        /// smoothPaths(): an odometry increment of exactly zero says the robot stood still
        /// (wheels that did not turn): its two poses are tied as tightly as the first start
        /// pose, not by the increment's covariance (a motion model's noise floor). More
        /// accurate on the simul-landmarks rawlogs, which start standing, and on MRCLAM
        /// (doc/multirobot.md §3).
        bool zero_odometry_stands_still = true;
        /// smoothPaths(): a robot's readings more than this apart [s] (0: never) split its
        /// path; each round, a part after such a gap is moved onto the robot's odometry from the
        /// part before when that raises the fraction of its readings that fit a landmark also
        /// read outside it by more than reanchor_gain (reanchorAfterGaps()).
        double reanchor_gap = 0;
        double reanchor_gain = 0.1;
        /// smoothPaths(): each round after the first maps the readings onto the previous
        /// round's landmarks, at their least-squares positions and with their mapped covariance
        /// (a reading that fits none starts a landmark), instead of onto an empty map; and
        /// every map along a path widens each reading's covariance by the odometry covariance
        /// of the step into its pose, so that a landmark read from close by on two passes is
        /// not split by the paths' small disagreement. More accurate at high noise on the
        /// simul-landmarks rawlogs (doc/multirobot.md §3).
        bool reassociate = false;

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
    } options;

    /// \param map_template its insertion options are those of every map made along a path
    /// (the filter's), but D0 = options.D0
    explicit TeamPathSmoother(const CVisualLandmarksMap& map_template);

    /// @name CMultiRobotVisualSLAM::TStepObserver: what the run is made of
    /// @{
    /// Forgets the run recorded so far.
    void onReset(const std::vector<mrpt::math::TPose2D>& start_poses, double initial_std_xy,
                 double initial_std_phi) override;
    void onRobotStep(size_t step, size_t robot, const core::TOdometryGaussian& motion,
                     const std::vector<TLandmarkMeasurement>& z,
                     const std::vector<CMultiRobotVisualSLAM::TRobotReading>& readings) override;
    /// @}

    /** The map of every measurement fused since reset(), made again along the final path of
     *  particle `p` (mapping with known poses): frame by frame in the order of the run, each
     *  robot's measurements at that particle's pose of the step, fused by
     *  CVisualLandmarksMap::fuseFrame() (sensor by sensor, each sensor's measurements to
     *  distinct landmarks in the order options.nearest_pair_first chooses) with the filter's
     *  insertion options but D0 = options.D0; then the landmarks seen fewer than
     *  minTimesSeen() times are removed. The poses do not move, so a wrong
     *  association here costs the map only, not the paths, and the gate can be wider than
     *  the filter's. `correspondences` (if given) gets those of the map's landmarks, in the
     *  order of the run. \pre registered with the filter before its reset() */
    CVisualLandmarksMap mapAlongPath(const TTeamParticle& p,
                                     std::vector<TCorrespondence>* correspondences = nullptr) const;
    /// The fewest measurements a landmark of a map along a path keeps: options.min_seen_fraction
    /// of the robot steps with landmark measurements recorded since reset(), rounded up.
    unsigned int minTimesSeen() const;

    /// The team's paths and map after smoothPaths().
    struct TSmoothedTeam {
        /// one per robot, oldest first, as CMultiRobotVisualSLAM::pathOf()
        std::vector<std::vector<std::pair<double, mrpt::math::TPose2D>>> paths;
        CVisualLandmarksMap map;  ///< mapped along `paths` as mapAlongPath() maps
        /// those `map` was made with, as mapAlongPath() gives them
        std::vector<TCorrespondence> correspondences;
        size_t iterations = 0;        ///< least-squares iterations, all rounds
        size_t readings = 0;          ///< in the last round's least squares
        size_t outlier_readings = 0;  ///< of those, beyond the Huber threshold
        size_t reanchored = 0;        ///< parts of paths reanchorAfterGaps() moved, all rounds
        /// the cost (PlanarPoseLandmarkGraph::cost()) of `paths` and `map` through
        /// `correspondences`, the landmarks at their mapped positions: what the output leaves
        /// unexplained of the odometry and readings
        double cost = 0;
        /// per robot (distance, turn), with options.odometry_scale_std > 0
        std::vector<Eigen::Vector2d> odometry_scales;
    };
    /** The most probable paths given every odometry increment and reading since reset() and
     *  the associations of the map along particle `p`'s path: options.rounds times, map along
     *  the current paths (mapAlongPath()'s rules, the landmarks below the count threshold left
     *  out; with options.reassociate, after the first round from the round before's
     *  landmarks, seedsFrom()), then solve the PlanarPoseLandmarkGraph of the start poses
     *  (the first robot's fixed, the others with the filter's initial_std_*), the odometry
     *  Gaussians (stepCovariance(); with options.odometry_scale_std, scaled by one distance
     *  and one turn scale per robot, estimated with the rest), the readings of the mapped
     *  landmarks and of the other robots (Huber); with options.reanchor_gap,
     *  reanchorAfterGaps() after each mapping; finally map along the result.
     *  \pre registered with the filter before its reset() */
    TSmoothedTeam smoothPaths(const TTeamParticle& p) const;

    /// One sensor's TSensorPoseCorrection and TSensorTiltCorrection: `sensor` as
    /// TLandmarkMeasurement::sensor.
    struct TSensorPoseCheck {
        size_t robot = 0;
        uint16_t sensor = 0;
        core::TSensorPoseCorrection correction;
        /// of its 3D readings (none for the planar model's) of landmarks read more than once
        std::optional<core::TSensorTiltCorrection> tilt;
        /// How much higher its 3D readings put the landmarks it shares with another sensor
        /// (`robot`, `sensor`) than that one's do, per such sensor (two or more shared).
        struct THeightAgainst {
            size_t robot = 0;
            uint16_t sensor = 0;
            core::TSensorHeightOffset offset;
        };
        std::vector<THeightAgainst> heights;
    };
    /** Per robot and sensor, the correction of the sensor's pose on the robot that best
     *  explains the readings of the map along particle `p`'s path: each reading of a landmark
     *  paired with the same sensor's previous reading of it, up to 3 steps before, through the
     *  robot's odometry between the two; the sensor's tilt from the heights of all its
     *  readings of each landmark; and its heights against each other sensor's, the landmarks of
     *  the two paired by place across and descriptor, not by height (a sensor stated too high
     *  maps its own landmarks above the other's). Robots and sensors without such pairs are
     *  left out.
     *  \pre registered with the filter before its reset() */
    std::vector<TSensorPoseCheck> sensorPoseChecks(const TTeamParticle& p) const;

  private:
    /// A robot's measurements of one step from one sensor: `step` indexes that step in the path
    /// (0: the start poses).
    struct TFusedFrame {
        size_t step, robot;
        std::vector<TLandmarkMeasurement> z;
        std::vector<CMultiRobotVisualSLAM::TRobotReading> readings;
    };
    std::vector<TFusedFrame> m_fusedFrames;  ///< those with measurements or readings
    /// Each step's odometry Gaussians, [step − 1][robot].
    std::vector<std::vector<core::TOdometryGaussian>> m_motions;
    std::vector<mrpt::math::TPose2D> m_startPoses;
    double m_initialStdXY = 0, m_initialStdPhi = 0;  ///< the filter's initial_std_*

    size_t robotCount() const { return m_startPoses.size(); }
    /// A particle's team poses per step of its path, [step][robot] (0: the start poses).
    using TTeamPath = std::vector<std::vector<mrpt::math::TPose2D>>;
    /// `p`'s path, which must hold the start and one step per step recorded.
    TTeamPath recordedPathOf(const TTeamParticle& p) const;
    /// mapAlongPath() along `path`; `ids` (if given) gets, per fused frame and measurement,
    /// the landmark it went to, or std::nullopt if that landmark was removed.
    using TFrameIds = std::vector<std::vector<std::optional<uint32_t>>>;
    /// An empty map with the options of maps along paths (the filter's, D0 = options.D0).
    CVisualLandmarksMap emptyMap() const;
    /// With `seeds` (options.reassociate), the map starts from their landmarks, unseen.
    CVisualLandmarksMap mapAlong(const TTeamPath& path, TFrameIds* ids,
                                 const CVisualLandmarksMap* seeds = nullptr) const;
    /// The odometry covariance of step `step` (≥ 1) of robot `robot` as smoothPaths() weighs
    /// it: × options.motion_cov_factor, or as tight as the first start pose where the robot
    /// stood (options.zero_odometry_stands_still).
    Eigen::Matrix3d stepCovariance(size_t step, size_t robot) const;
    /// The pose variable of robot `robot` at step `step` in graphOf()'s graph.
    size_t nodeOf(size_t step, size_t robot) const { return step * robotCount() + robot; }
    /// The least squares of `path`, the landmarks of `map` (made along it; `pointOf`: landmark
    /// id → point, at the landmark's mapped position) and the readings `ids` associates: the
    /// start poses' priors (the first robot's fixed, the others with the filter's
    /// initial_std_*), the odometry (stepCovariance(); scale variables from `scales`, one per
    /// robot, with options.odometry_scale_std), the readings of the landmarks and of other robots.
    PlanarPoseLandmarkGraph graphOf(const TTeamPath& path, const CVisualLandmarksMap& map,
                                    const TFrameIds& ids,
                                    const std::vector<Eigen::Vector2d>& scales,
                                    std::map<uint32_t, size_t>& pointOf) const;
    /// The landmarks of `map` (made along a path) at their positions solved in `graph`
    /// (`pointOf`: landmark id → point), unseen: the next round's seeds.
    CVisualLandmarksMap seedsFrom(const CVisualLandmarksMap& map,
                                  const PlanarPoseLandmarkGraph& graph,
                                  const std::map<uint32_t, size_t>& pointOf) const;
    /// The correspondences of mapAlong()'s `ids`, those of removed landmarks left out.
    std::vector<TCorrespondence> correspondencesOf(const TFrameIds& ids) const;
    /** Of the landmark readings in fused frames `frames` (one robot's), the fraction that fit
     *  (squared Mahalanobis distance < 9.21, 99 % for 2 dof) a landmark of `map` (made along
     *  `path`, `ids` its associations) that readings outside `frames` also went to. */
    double supportedFraction(const std::vector<size_t>& frames, const TTeamPath& path,
                             const CVisualLandmarksMap& map, const TFrameIds& ids) const;
    /** Per robot, its path split where its landmark readings are more than
     *  options.reanchor_gap apart; in the order of the run, each part after a gap (the gap
     *  included) is replaced by the robot's odometry (scaled by `scales`, if any) from the
     *  last pose before it, where that raises the part's supportedFraction() by more than
     *  options.reanchor_gain. `map` and `ids` follow `path`; maps along candidate paths start
     *  from `seeds` (mapAlong()). \return how many parts moved */
    size_t reanchorAfterGaps(TTeamPath& path, const std::vector<double>& times,
                             const std::vector<Eigen::Vector2d>& scales, CVisualLandmarksMap& map,
                             TFrameIds& ids, const CVisualLandmarksMap* seeds) const;

    CVisualLandmarksMap m_template;  ///< empty; the options of the maps along paths
};

}  // namespace mrpt_vslam::multirobot
