#pragma once

#include <mrpt/math/TPose2D.h>

#include <Eigen/Core>
#include <vector>

namespace mrpt_vslam::core {

/** Two readings of one point by one sensor, from robot poses x_i and x_j = x_i ⊕ u, in the
 *  robot frame as the sensor's pose on the robot puts them. */
struct TReadingPair {
    Eigen::Vector2d z_i, z_j;
    Eigen::Matrix2d R_i, R_j;  ///< their covariances
    mrpt::math::TPose2D u;     ///< the odometry from x_i to x_j, in x_i's frame
    Eigen::Matrix3d Q;         ///< its covariance
};

/** The planar correction δ = (t, θ) of a sensor's pose on the robot that best explains pairs of
 *  readings of the same point (ours; doc/multirobot.md, "Checking the sensor poses"): with the
 * sensor at δ ⊕ (its pose), a reading z lies at δ ⊕ z = R(θ) z + t in the robot frame, and the
 * point read from x_i and from x_j = x_i ⊕ u is one: r = (δ ⊕ z_i) − u ⊕ (δ ⊕ z_j) = 0. A
 * translation t shows only where the robot turns, θ where it moves. An odometry whose heading
 * drifts by ε [rad/m] looks like a sensor turned by about ε times the readings' range: the two are
 * not told apart. */
struct TSensorPoseCorrection {
    Eigen::Vector3d delta = Eigen::Vector3d::Zero();  ///< (t_x [m], t_y [m], θ [rad])
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();    ///< its covariance
    size_t pairs = 0;
    size_t outlier_pairs = 0;  ///< whitened residual beyond the Huber threshold

    /** Weighted least squares over `pairs` (Gauss-Newton; Huber on each pair's whitened
     *  residual norm at `huber` σ; a weak prior N(0, diag(1 m², 1 m², π²)) keeps t solvable
     *  when the robot never turns), from θ = 0, ±π/2 and π: the least cost is kept. */
    static TSensorPoseCorrection estimate(const std::vector<TReadingPair>& pairs, double huber = 3);
    /// The whitened residual of `p` with this correction.
    Eigen::Vector2d whitenedResidual(const TReadingPair& p) const;
    /// Σ_θθ (Σ⁻¹)_θθ, θ's variance over its variance were t known: about 1 where the robot's
    /// path tells a turn from a move, large on paths of one curvature (circles), where a turn
    /// passes for a move.
    double turnConfounding() const;
    /// [m] the largest σ of t (the square root of its covariance's largest eigenvalue).
    double largestMoveStd() const;
};

}  // namespace mrpt_vslam::core
