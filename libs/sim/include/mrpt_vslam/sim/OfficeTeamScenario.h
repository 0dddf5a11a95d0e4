#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt_vslam/sim/OdometrySimulator.h>
#include <mrpt_vslam/sim/OfficeWorld.h>
#include <mrpt_vslam/sim/Scenario.h>
#include <mrpt_vslam/sim/StereoRenderer.h>
#include <mrpt_vslam/sim/TexturePainter.h>
#include <mrpt_vslam/sim/WaypointTrajectory.h>

#include <string>
#include <vector>

namespace mrpt_vslam::sim {

/** What the robots of a team saw during a run (ground-truth corners seen by both cameras of a
 *  stereo head, see StereoRenderer::seesPoint). */
struct TTeamStatistics {
    size_t corners = 0;               ///< ground-truth corners in the world
    std::vector<size_t> seen;         ///< per robot: corners seen in at least one frame
    std::vector<size_t> tracked;      ///< per robot: corners seen in 3 consecutive frames or more
    size_t tracked_by_several = 0;    ///< corners tracked by two robots or more
    std::vector<double> path_length;  ///< [m] per robot, ground truth
};

/** The multi-robot experiment of Gil et al. (2010), Sec. 6: two or three robots with a
 *  forward-looking stereo head (Videre STH-MDCS2) drive through an office-like 17 × 8 m area;
 *  robot R1 starts at the origin of the common frame, R2 at (−4, 0, 0°) ("The relative starting
 *  position of the other robot respect to this reference is (x, y, θ) = (−4, 0, 0)").
 *
 *  Per step k (t = start_time + k·frame_period), for each robot R1..RK in order:
 *  1. ground-truth pose from its waypoint path (WaypointTrajectory, [Trajectory_R<n>]);
 *  2. noisy odometry (OdometrySimulator, own random stream per robot) → cumulative
 *     CObservationOdometry `R<n>_ODOM`, starting at the true start pose;
 *  3. the stereo pair rendered from the textured world (StereoRenderer, own image-noise stream
 *     per robot) → CObservationStereoImages `R<n>_STEREO` with external PNG images;
 *  4. CObservationRobotPose `R<n>_GROUND_TRUTH`.
 *  The rawlog is observation-only; beside it `NAME.groundtruth_R<n>.tum`,
 *  `NAME.odometry_R<n>.tum`, `NAME.landmarks.txt` (the designed corners) and `NAME.topview.png`.
 *
 *  loadConfig() checks every path against the world: each pose keeps `robot_radius` from walls
 *  and furniture, and the camera never faces a wall or furniture closer than `min_view_distance`.
 */
class OfficeTeamScenario : public Scenario {
  public:
    /// @name Parameters, one object per ini section
    /// @{
    OfficeWorld world;                             ///< [World]
    TexturePainter textures;                       ///< [Textures]
    StereoRenderer stereo;                         ///< [StereoCamera]
    mrpt::poses::CPose3D camera_on_robot;          ///< [CameraOnRobot] left camera on robot
    std::vector<WaypointTrajectory> trajectories;  ///< [Trajectory_R1], [Trajectory_R2], ...
    OdometrySimulator odometry;                    ///< [Odometry], shared by all robots
    double robot_radius = 0.3;                     ///< [Robots] radius [m]
    double min_view_distance = 0.6;                ///< [Robots] min_view_distance [m]
    double start_time = 1325376000.0;              ///< [Dataset] start_time [s]
    /// @}

    /// Robots simulated when TSimulationOptions::robots is not given.
    static constexpr int kDefaultRobots = 2;

    OfficeTeamScenario();

    std::string name() const override { return "office-team"; }
    void loadConfig(const mrpt::config::CConfigFileBase& cfg) override;
    TSimulationSummary run(const TSimulationOptions& options) override;

    /// Name of robot `index` (0-based): "R1", "R2", ...
    static std::string robotName(size_t index);
    /// Sensor label of robot `index` (0-based): label(0, "STEREO") = "R1_STEREO".
    static std::string label(size_t index, const std::string& sensor);
    /// Ground-truth poses of every robot (`robots` first ones) for `steps` steps.
    std::vector<std::vector<mrpt::math::TPose2D>> paths(int robots, int steps) const;
    /// Statistics of the last run().
    const TTeamStatistics& statistics() const { return m_statistics; }

  private:
    /// Throws core::UsageError naming the section of the first path that leaves free space.
    void checkPaths() const;
    /** Fills the corner counts of m_statistics from the longest run of consecutive frames in
     *  which each robot (first index) saw each corner (second index). */
    void countCorners(const std::vector<std::vector<int>>& best_run);

    TTeamStatistics m_statistics;
};

}  // namespace mrpt_vslam::sim
