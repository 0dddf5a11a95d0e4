#pragma once

#include <mrpt/core/bits_math.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/math/TPose3D.h>
#include <mrpt_vslam/core/TumTrajectory.h>

#include <Eigen/Core>
#include <limits>
#include <utility>
#include <vector>

namespace mrpt_vslam::core {

/** Options of evaluateTrajectory(). */
struct TTrajectoryMetricsOptions {
    double time_tolerance = 0.05;                   ///< [s] max |t_est - t_gt| of a matched pair
    double heading_threshold = mrpt::DEG2RAD(5.0);  ///< [rad] for heading_share_under_threshold
    bool align_se2 = false;  ///< first align the estimate to the ground truth (alignSE2())
    /// [s] only the estimate's poses later than this (e.g. after a gap in a live run)
    double after = -std::numeric_limits<double>::infinity();
    /** Fewer matched estimate poses than this share of the estimate's is an error: the estimate
     *  and the ground truth hardly overlap in time (e.g. another dataset's ground truth). */
    double min_matched_share = 0.5;
};

/** Errors of an estimated trajectory against ground truth, over the matched frames. */
struct TTrajectoryMetrics {
    size_t estimate_poses = 0;      ///< poses in the estimate
    size_t ground_truth_poses = 0;  ///< poses in the ground truth
    /// Rigid planar transform applied to the estimate (identity without alignment).
    mrpt::math::TPose2D alignment{0, 0, 0};

    /// @name Per matched frame (estimate order), for plots
    /// @{
    std::vector<double> timestamps;       ///< [s] estimate timestamps
    std::vector<double> position_errors;  ///< [m] |p_est - p_gt| (3D)
    std::vector<double> heading_errors;   ///< [rad] yaw_est - yaw_gt wrapped to (-π, π]
    /// @}

    /// @name Summary (NaN when no frame matched)
    /// @{
    double ate_rmse = 0, ate_mean = 0, ate_max = 0;              ///< [m]
    double heading_rmse = 0, heading_mean = 0, heading_max = 0;  ///< [rad] of |heading error|
    double heading_share_under_threshold = 0;  ///< [0..1] frames with |error| <= threshold
    /// @}

    size_t matchedPoses() const { return timestamps.size(); }
};

/** Pairs (estimate index, ground-truth index) matched by nearest timestamp within `tolerance`
 *  [s]; every estimate pose is matched to at most one ground-truth pose. */
std::vector<std::pair<size_t, size_t>> associateByTime(const TumTrajectory& estimate,
                                                       const TumTrajectory& ground_truth,
                                                       double tolerance);

/** Closed-form least-squares rigid planar transform T = (x, y, θ) minimising
 *  Σ |R(θ) a_i + t - b_i|² over the XY coordinates (Umeyama 1991 without scale, in 2D).
 *  Throws std::invalid_argument on different sizes or fewer than 2 points. */
mrpt::math::TPose2D alignSE2(const std::vector<mrpt::math::TPoint2D>& a,
                             const std::vector<mrpt::math::TPoint2D>& b);

/** Applies a planar transform (alignSE2()) to a 3D pose: XY rotated and shifted, yaw increased. */
mrpt::math::TPose3D applySE2(const mrpt::math::TPose2D& transform, const mrpt::math::TPose3D& p);

/** ATE and heading errors of `estimate` against `ground_truth` (doc/data-formats.md). Throws
 *  std::runtime_error when fewer than `min_matched_share` of the estimate's poses can be matched
 *  in time. */
TTrajectoryMetrics evaluateTrajectory(const TumTrajectory& estimate,
                                      const TumTrajectory& ground_truth,
                                      const TTrajectoryMetricsOptions& options = {});

/** Normalised estimation error squared e^T P^-1 e. Throws std::invalid_argument on size mismatch
 *  or a covariance that is not positive definite. */
double nees(const Eigen::VectorXd& error, const Eigen::MatrixXd& cov);

/** NEES of a planar pose (x, y, φ), heading difference wrapped to (-π, π]. */
double poseNEES(const mrpt::math::TPose2D& estimate, const mrpt::math::TPose2D& truth,
                const Eigen::Matrix3d& cov);

/** NEES of a 3D pose in MRPT's (x, y, z, yaw, pitch, roll) order, angle differences wrapped. */
double poseNEES(const mrpt::math::TPose3D& estimate, const mrpt::math::TPose3D& truth,
                const Eigen::Matrix<double, 6, 6>& cov);

/** Two-sided χ² consistency bounds for the NEES averaged over `runs` independent runs (or
 *  frames) of dimension `dof`: [χ²⁻¹(α/2, runs·dof), χ²⁻¹(1-α/2, runs·dof)] / runs, with
 *  α = 1 - confidence (Bar-Shalom et al. 2001, §5.4).
 *  Uses mrpt::math::chi2inv(), the Wilson-Hilferty approximation: close for large runs·dof
 *  (< 0.1% off at 150), coarse for a few dof, where the lower bound is clamped at 0.
 *  Throws std::invalid_argument on dof or runs = 0 or confidence outside (0, 1). */
std::pair<double, double> chi2Bounds(unsigned int dof, double confidence = 0.95,
                                     unsigned int runs = 1);

}  // namespace mrpt_vslam::core
