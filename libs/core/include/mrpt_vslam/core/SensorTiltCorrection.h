#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace mrpt_vslam::core {

/** One 3D reading of a point, in the robot frame as the sensor's stated pose on the robot puts
 *  it, and its covariance. */
struct TPointReading {
    Eigen::Vector3d z = Eigen::Vector3d::Zero();  ///< [m]
    Eigen::Matrix3d R = Eigen::Matrix3d::Zero();  ///< [m²]
};

/** The tilt of a sensor on a robot that moves on a plane, read from the heights of the points
 *  it reads (ours; doc/multirobot.md, "Checking the sensor poses"). With the sensor turned on
 *  the robot by R_c = R_y(pitch) R_x(roll) about its stated position s (robot axes: x ahead,
 *  y left, z up; a positive pitch turns x down, a positive roll turns y up), a reading z lies
 *  at s + R_c (z − s), and a point's height there is the same from every pose of a planar path:
 *  nᵀ z = c for all readings of the point, with n = R_cᵀ e_z and c the point's own. The
 *  odometry does not enter: neither its drift nor its noise biases the tilt. A pitch shows where
 *  the robot moves towards points, a roll where points pass it sideways (turns); a height
 *  offset does not show. */
struct TSensorTiltCorrection {
    Eigen::Vector2d delta = Eigen::Vector2d::Zero();  ///< (pitch, roll) [rad]
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();    ///< its covariance
    size_t readings = 0;                              ///< of points read more than once
    size_t points = 0;                                ///< read more than once
    size_t outlier_readings = 0;  ///< whitened residual beyond the Huber threshold

    /** Weighted least squares over the readings of each point of `points` (Gauss-Newton on
     *  pitch and roll, each point's height eliminated; the variance of a reading's height is
     *  nᵀ R n; Huber at `huber` σ; a weak prior N(0, π²) on each angle). Points read once tell
     *  nothing and are left out. */
    static TSensorTiltCorrection estimate(const std::vector<std::vector<TPointReading>>& points,
                                          double huber = 3);
};

}  // namespace mrpt_vslam::core
