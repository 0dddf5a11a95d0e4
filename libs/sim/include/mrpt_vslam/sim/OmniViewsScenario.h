#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt_vslam/sim/OdometrySimulator.h>
#include <mrpt_vslam/sim/OfficeWorld.h>
#include <mrpt_vslam/sim/OmniRenderer.h>
#include <mrpt_vslam/sim/Scenario.h>
#include <mrpt_vslam/sim/TexturePainter.h>
#include <mrpt_vslam/sim/WaypointTrajectory.h>

#include <string>
#include <vector>

namespace mrpt_vslam::sim {

/** The experiment of Valiente et al. 2015 (view-based omnidirectional EKF SLAM): one robot with an
 *  upward-looking central omnidirectional camera (unified sphere model) drives through an
 *  indoor area of rooms along a corridor, with textured walls, furniture, floor and ceiling
 *  (OfficeWorld: the rooms' inner walls are full-height partitions with door gaps).
 *
 *  Per frame k (t = start_time + k·frame_period):
 *  1. ground-truth pose from the waypoint controller (WaypointTrajectory);
 *  2. noisy odometry increment (OdometrySimulator) → CActionRobotMovement2D (Gaussian model);
 *  3. the image ray cast from the textured world (OmniRenderer), saved as PNG beside the rawlog;
 *  4. a sensory frame with the OMNICAM image and the GROUND_TRUTH observation.
 *  Beside the rawlog (format #1): `NAME.groundtruth.tum`, `NAME.odometry.tum` and
 *  `NAME.landmarks.txt` (the designed texture corners).
 *
 *  loadConfig() checks that every pose of the full path keeps `robot_radius` from walls and
 *  furniture. Odometry and image noise draw from independent random streams. */
class OmniViewsScenario : public Scenario {
  public:
    /// @name Parameters, one object per ini section
    /// @{
    OfficeWorld world;                                         ///< [World]
    TexturePainter textures;                                   ///< [Textures]
    OmniRenderer renderer;                                     ///< [Camera]
    mrpt::poses::CPose3D camera_on_robot{0, 0, 0.4, 0, 0, 0};  ///< [CameraOnRobot]
    WaypointTrajectory trajectory;                             ///< [Trajectory]
    OdometrySimulator odometry;                                ///< [Odometry]
    double robot_radius = 0.3;                                 ///< [Robot] radius [m]
    double start_time = 1325376000.0;                          ///< [Dataset] start_time [s]
    /// @}

    std::string name() const override { return "omni-views"; }
    void loadConfig(const mrpt::config::CConfigFileBase& cfg) override;
    TSimulationSummary run(const TSimulationOptions& options) override;
};

}  // namespace mrpt_vslam::sim
