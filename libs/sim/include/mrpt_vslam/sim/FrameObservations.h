#pragma once

#include <mrpt/img/TStereoCamera.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/system/datetime.h>
#include <mrpt_vslam/sim/DetectionSimulator.h>

#include <functional>
#include <string>

namespace mrpt_vslam::sim {

/// Sensor labels of the datasets (doc/data-formats.md).
inline constexpr const char* kImageLabel = "OMNICAM";
inline constexpr const char* kBearingsLabel = "OMNICAM_BEARINGS";
inline constexpr const char* kGroundTruthLabel = "GROUND_TRUTH";

/** `OMNICAM` image observation whose image is stored externally as `image_file` (relative to
 *  the rawlog's `_Images` directory); cameraParams holds only the image size. */
mrpt::obs::CObservationImage::Ptr makeImageObservation(const std::string& image_file, int width,
                                                       int height,
                                                       const mrpt::poses::CPose3D& camera_on_robot,
                                                       mrpt::Clock::time_point stamp);

/** `OMNICAM_BEARINGS` bearing-only observation: range NaN, yaw = φ, pitch = −(π/2 − θ),
 *  landmarkID −1; per-measurement covariances diag(0, σ_φ(θ)², σ_θ(θ)²) from `std_at_theta`
 *  (validCovariances = true; MRPT then serializes those instead of sensor_std_yaw/pitch, which
 *  get `angular_std` = (σ_yaw, σ_pitch) [rad] at a reference θ in memory only); fieldOfView_yaw =
 * 2π, fieldOfView_pitch = 2·max_theta (the full cone of detection). */
mrpt::obs::CObservationBearingRange::Ptr makeBearingObservation(
    const TFrameDetections& frame, const mrpt::poses::CPose3D& camera_on_robot,
    const std::function<Eigen::Vector2d(double theta)>& std_at_theta,
    const Eigen::Vector2d& angular_std, double max_theta, mrpt::Clock::time_point stamp);

/** Robot pose observation labelled `label` (`GROUND_TRUTH`, or `R1_GROUND_TRUTH` ... in a team):
 *  exact pose, zero covariance. */
mrpt::obs::CObservationRobotPose::Ptr makeGroundTruthObservation(
    const mrpt::poses::CPose3D& robot_in_world, mrpt::Clock::time_point stamp,
    const std::string& label = kGroundTruthLabel);

/** Odometry observation labelled `label` (e.g. `R1_ODOM`): the cumulative odometry pose
 *  (not an increment), without encoder ticks or velocities. */
mrpt::obs::CObservationOdometry::Ptr makeOdometryObservation(const std::string& label,
                                                             const mrpt::poses::CPose2D& odometry,
                                                             mrpt::Clock::time_point stamp);

/** Rectified stereo pair labelled `label` (e.g. `R1_STEREO`) whose images are stored externally
 *  as `left_file` and `right_file` (relative to the rawlog's `_Images` directory): both cameras
 *  get the intrinsics of `camera` (no distortion), `rightCameraPose` its left-to-right pose and
 *  `cameraPose` the left camera's pose on the robot. */
mrpt::obs::CObservationStereoImages::Ptr makeStereoObservation(
    const std::string& label, const std::string& left_file, const std::string& right_file,
    const mrpt::img::TStereoCamera& camera, const mrpt::poses::CPose3D& camera_on_robot,
    mrpt::Clock::time_point stamp);

}  // namespace mrpt_vslam::sim
