#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CObservationVisualLandmarks.h>
#include <mrpt_vslam/core/USurfDescriptor.h>

#include <Eigen/Core>

#include <cmath>

#include <vector>

namespace mrpt_vslam::multirobot {

/** One stereo observation o_t = (z_t, d_t) of paper 003 (Sec. 3), moved from the camera frame
 *  into the robot frame, which does not depend on the particle: the point and R_t rotated by the
 *  camera's pose on the robot. */
struct TLandmarkMeasurement {
    Eigen::Vector3d z = Eigen::Vector3d::Zero();  ///< point in the robot frame [m]
    Eigen::Matrix3d R = Eigen::Matrix3d::Zero();  ///< its covariance R_t in the robot frame [m²]
    core::USurfDescriptor::TDescriptor d{};       ///< U-SURF descriptor d_t
    double depth = 0;      ///< distance along the optical axis [m]: B-selection key
    int64_t track_id = -1;  ///< front-end track (diagnostics only; never used to associate)
};

/** The same measurement in the map frame for one particle's robot pose x:
 *  z_w = g⁻¹(x, z) = R(θ) z + (x, y, 0), R_w = R(θ) R R(θ)^T. */
struct TMapMeasurement {
    Eigen::Vector3d z;
    Eigen::Matrix3d R;
};

/** The measurements of a `CObservationVisualLandmarks` (one per CLandmark: pose_mean in the
 *  camera frame, pose_cov_* = R_t, U-SURF in features[0].descriptors.SURF), in the robot frame.
 *  \throw std::runtime_error naming the label if a landmark has no 64-D SURF descriptor or a
 *  non-finite point or covariance. */
std::vector<TLandmarkMeasurement> measurementsFromObservation(
    const mrpt::obs::CObservationVisualLandmarks& obs);

/** The (at most) B measurements with the smallest depth, the most precise for a stereo pair,
 *  in that order (ties: lower track id); all of them if B = 0 or fewer. */
std::vector<TLandmarkMeasurement> selectNearest(std::vector<TLandmarkMeasurement> z, size_t B);

/// The measurement in the map frame seen from `robot`.
inline TMapMeasurement toMapFrame(const TLandmarkMeasurement& m, const mrpt::math::TPose2D& robot)
{
    const double c = std::cos(robot.phi), s = std::sin(robot.phi);
    Eigen::Matrix3d rot;
    rot << c, -s, 0, s, c, 0, 0, 0, 1;
    return {rot * m.z + Eigen::Vector3d(robot.x, robot.y, 0), rot * m.R * rot.transpose()};
}

}  // namespace mrpt_vslam::multirobot
