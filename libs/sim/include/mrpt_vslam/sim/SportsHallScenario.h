#pragma once

#include <mrpt/poses/CPose3D.h>
#include <mrpt_vslam/core/PajdlaBaksteinCamera.h>
#include <mrpt_vslam/sim/CeilingLights.h>
#include <mrpt_vslam/sim/DetectionSimulator.h>
#include <mrpt_vslam/sim/LightBlobRenderer.h>
#include <mrpt_vslam/sim/OdometrySimulator.h>
#include <mrpt_vslam/sim/Scenario.h>
#include <mrpt_vslam/sim/WaypointTrajectory.h>

#include <cmath>

namespace mrpt_vslam::sim {

/** The experiment of Gamallo et al. (2013), Sec. IV: a Pioneer 3-DX in a sports hall with
 *  14 ceiling lights 6.5 m high (Table I), an upward IR fisheye camera 1.8 m above the floor,
 *  320 images at 1 Hz over ~88 m, v ≤ 0.30 m/s, ω ≤ 0.52 rad/s, returning to the start at frames
 *  ~205, ~298 and ~318; big windows on one side wash out the lights near them for a while.
 *
 *  Per frame k (t = k·frame_period):
 *  1. ground-truth pose from the waypoint controller (WaypointTrajectory);
 *  2. noisy odometry increment (OdometrySimulator) → CActionRobotMovement2D (Gaussian model);
 *  3. visible lights, spurious reflections and bearings (DetectionSimulator);
 *  4. the image (LightBlobRenderer), saved as PNG beside the rawlog;
 *  5. a sensory frame with OMNICAM image, OMNICAM_BEARINGS and GROUND_TRUTH observations.
 *
 *  Random streams (see RandomStreams.h): odometry, detections and image noise are independent,
 *  so e.g. --no-images or other image-noise settings leave odometry and bearings unchanged. */
class SportsHallScenario : public Scenario {
  public:
    /// @name Parameters, one object per ini section
    /// @{
    core::PajdlaBaksteinCamera camera;                         ///< [Camera] model of Eq. 1
    mrpt::poses::CPose3D camera_on_robot{0, 0, 1.8, 0, 0, 0};  ///< [CameraOnRobot]
    CeilingLights lights;                                      ///< [Lights]
    WaypointTrajectory trajectory;                             ///< [Trajectory]
    OdometrySimulator odometry;                                ///< [Odometry]
    DetectionSimulator detections;                             ///< [Detections]
    LightBlobRenderer renderer;                                ///< [Image]
    double start_time = 1325376000.0;  ///< [s] Unix time of frame 0 ([Dataset] start_time)
    /// [rad] θ at which sensor_std_yaw/pitch of the bearings are evaluated
    /// ([Dataset] bearing_std_reference_theta_deg)
    double bearing_std_reference_theta = M_PI / 4;
    /// @}

    std::string name() const override { return "sports-hall"; }
    void loadConfig(const mrpt::config::CConfigFileBase& cfg) override;
    TSimulationSummary run(const TSimulationOptions& options) override;
};

}  // namespace mrpt_vslam::sim
