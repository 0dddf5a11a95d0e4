#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/core/OdometryGaussian.h>

#include <Eigen/Core>
#include <functional>
#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace mrpt_vslam::core {

/// The odometry from step `from` to step `to` > `from`, `motion(s)` that from s − 1 to s,
/// composed (mean and covariance).
std::pair<mrpt::math::TPose2D, Eigen::Matrix3d> composedOdometry(
    const std::function<const TOdometryGaussian&(size_t)>& motion, size_t from, size_t to);

/** Two readings of one point by one sensor, from robot poses x_i and x_j = x_i ⊕ u, in the
 *  robot frame as the sensor's pose on the robot puts them. */
struct TReadingPair {
    Eigen::Vector2d z_i, z_j;
    Eigen::Matrix2d R_i, R_j;  ///< their covariances
    mrpt::math::TPose2D u;     ///< the odometry from x_i to x_j, in x_i's frame
    Eigen::Matrix3d Q;         ///< its covariance
    /// the steps of x_i and x_j: the pairs of the same two steps share u and its error (a
    /// pair with step_j <= step_i shares it with none)
    size_t step_i = 0, step_j = 0;
};

/** A bearing read by the sensor from x_j = x_i ⊕ u of the sensor's own position at x_i (a
 *  view-based map's observation of a view started at x_i; Valiente et al. 2015), in the robot
 *  frame as the sensor's stated pose on the robot puts it. */
struct TEarlierPoseBearing {
    Eigen::Vector2d sensor = Eigen::Vector2d::Zero();  ///< [m] the sensor's stated position
    double bearing = 0;                                ///< [rad]
    double var = 0;                                    ///< [rad²] its variance
    mrpt::math::TPose2D u;                             ///< the odometry from x_i to x_j
    Eigen::Matrix3d Q = Eigen::Matrix3d::Zero();       ///< its covariance
};

/** Pairs each reading of a point (`Key`) with the previous reading of the same point when that
 *  is at most `max_gap` steps before, through the odometry between the two steps (the steps'
 *  Gaussians composed). Readings are added in the order of their steps. */
template <class Key>
class ReadingPairing {
  public:
    /// `motion(key, s)`: the odometry Gaussian from step s − 1 to step s of the robot that
    /// read point `key`.
    explicit ReadingPairing(std::function<const TOdometryGaussian&(const Key&, size_t)> motion,
                            size_t max_gap = 3)
        : m_motion(std::move(motion)), m_maxGap(max_gap)
    {
    }
    /// The reading `z` (covariance `R`, robot frame) of point `key` at step `step`, and the pair
    /// it makes with the point's reading before, if any.
    std::optional<TReadingPair> add(const Key& key, size_t step, const Eigen::Vector2d& z,
                                    const Eigen::Matrix2d& R)
    {
        const TReading now{step, z, R};
        auto [it, first] = m_last.try_emplace(key, now);
        if (first) return std::nullopt;
        const TReading before = it->second;
        it->second = now;
        if (now.step <= before.step || now.step - before.step > m_maxGap) return std::nullopt;
        const auto [u, Q] =
            composedOdometry([&](size_t s) -> const TOdometryGaussian& { return m_motion(key, s); },
                             before.step, now.step);
        return TReadingPair{before.z, now.z, before.R, now.R, u, Q, before.step, now.step};
    }

  private:
    struct TReading {
        size_t step;
        Eigen::Vector2d z;
        Eigen::Matrix2d R;
    };
    std::function<const TOdometryGaussian&(const Key&, size_t)> m_motion;
    size_t m_maxGap;
    std::map<Key, TReading> m_last;
};

/** The planar correction δ = (t, θ) of a sensor's pose on the robot, and the scale k of its
 *  readings, that best explain pairs of readings of the same point (ours; doc/multirobot.md,
 *  "Checking the sensor poses"): with the sensor at δ ⊕ (its pose) and its readings k times as
 *  far as they say, a reading z lies at δ ⊕ k z = R(θ) k z + t in the robot frame, and the
 *  point read from x_i and from x_j = x_i ⊕ u is one: r = (δ ⊕ k z_i) − u ⊕ (δ ⊕ k z_j) = 0. A
 *  bearing b of the sensor's position c = δ ⊕ s at x_i (TEarlierPoseBearing) is that of
 *  v = u⁻¹ ⊕ c − c turned by θ: r = atan2(v) − θ − b (k plays no part). A translation t shows
 *  only where the robot turns, θ and k where it moves: θ across the readings, k along them. An
 *  odometry whose heading drifts by ε [rad/m] looks like a sensor turned by about ε times the
 *  readings' range, and one whose distances are k times too short like readings k times too
 *  long (a stereo baseline or a range unit off): the two are not told apart. */
struct TSensorPoseCorrection {
    Eigen::Vector3d delta = Eigen::Vector3d::Zero();  ///< (t_x [m], t_y [m], θ [rad])
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();    ///< its covariance (k unknown too)
    double scale = 1;                                 ///< [-] k
    double scale_std = 0;  ///< [-] its σ (δ unknown too); ∞ where k was not fitted
    /// k's variance over its variance were δ known, at the stated pose (δ = 0, k = 1): about 1
    /// where the path tells the scale from a turn and move of the sensor, large on paths of one
    /// curvature (circles); from kToldScaleConfounding on, k is held at 1
    double scale_confounding = 1;
    static constexpr double kToldScaleConfounding = 4;
    size_t pairs = 0;          ///< reading pairs and bearings
    size_t outlier_pairs = 0;  ///< whitened residual beyond the Huber threshold

    /** Weighted least squares over `pairs` and `bearings` (Gauss-Newton; Huber on each one's
     *  whitened residual norm at `huber` σ; a weak prior N((0, 0, 0, 1), diag(1 m², 1 m², π²,
     *  1)) on (t, θ, k) keeps t solvable when the robot never turns and k when it never moves),
     *  from θ = 0, ±π/2 and π and k = 1, each step halved until the cost falls: the least cost
     *  is kept. Without `fit_scale`, k stays 1 (readings whose scale is not the sensor's: points
     *  placed at a map's estimated heights), and so it does where the path does not tell k
     *  from δ (scale_confounding): on a circle, readings shrunk to the sensor (k → 0) at the
     *  circle's centre would explain every pair.
     *  The pairs of the same two steps share one odometry error: each such group is weighed
     *  with the joint covariance of its residuals, not as independent pairs, which would count
     *  the odometry's information once per point read. The pairs' gradient takes that
     *  covariance's own dependence on (t, θ, k) (errors in variables: the odometry's turn is
     *  in t's Jacobian), so that a noisy turn does not bias the estimate. */
    static TSensorPoseCorrection estimate(const std::vector<TReadingPair>& pairs,
                                          const std::vector<TEarlierPoseBearing>& bearings = {},
                                          double huber = 3, bool fit_scale = true);
    /// Whether the readings tell k: fitted, with σ under half its prior's (1) (bearings alone
    /// do not), on a path that tells it from δ (scale_confounding < 4).
    bool scaleTold() const { return scale_std < 0.5 && scale_confounding < kToldScaleConfounding; }
    /// The whitened residual of `p` with this correction.
    Eigen::Vector2d whitenedResidual(const TReadingPair& p) const;
    /// The whitened residual of `b` with this correction.
    double whitenedResidual(const TEarlierPoseBearing& b) const;
    /// Σ_θθ (Σ⁻¹)_θθ of `cov`, θ's variance over its variance were t known (k unknown either
    /// way): about 1 where the robot's path tells a turn from a move, large on paths of one
    /// curvature (circles), where a turn passes for a move.
    double turnConfounding() const;
    /// [m] the largest σ of t (the square root of its covariance's largest eigenvalue).
    double largestMoveStd() const;
};

}  // namespace mrpt_vslam::core
