#pragma once

#include <mrpt/math/TPose2D.h>

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

namespace mrpt_vslam::multirobot {

/** Planar robot poses (x, y, θ) and landmark points (x, y) tied by Gaussian factors, solved for
 *  the most probable values by Levenberg-Marquardt on the sparse normal equations (ours: the
 *  smoothing of the team filter's paths, doc/multirobot.md §3). Factors:
 *   - a prior on a pose: r = x − μ (angle wrapped);
 *   - odometry between two poses: r = x_i⁻¹ ⊕ x_j − u (u in x_i's frame, angle wrapped), or
 *     with an odometry scale variable s = (s_d, s_θ): u = (s_d u_x, s_d u_y, s_θ u_θ), for
 *     odometry whose distances and turns are off by a factor (commanded speeds);
 *   - a prior on a scale variable: r = s − μ;
 *   - a reading of a point, or of another pose's position, in a pose's frame:
 *     r = R(θ_i)ᵀ (p − t_i) − z.
 *  Readings are robust (Huber on the whitened residual's norm, by iteratively reweighted least
 *  squares): a few wrong associations pull with a bounded force. */
class PlanarPoseLandmarkGraph {
  public:
    size_t addPose(const mrpt::math::TPose2D& initial);
    size_t addPoint(const Eigen::Vector2d& initial);
    /// An odometry scale (distance, turn), starting at `initial`, with a prior N(mean, cov).
    size_t addOdometryScale(const Eigen::Vector2d& initial, const Eigen::Vector2d& mean,
                            const Eigen::Matrix2d& cov);

    void addPosePrior(size_t pose, const mrpt::math::TPose2D& mean, const Eigen::Matrix3d& cov);
    void addOdometry(size_t from, size_t to, const mrpt::math::TPose2D& increment,
                     const Eigen::Matrix3d& cov);
    /// The same, the increment scaled by odometry scale variable `scale`.
    void addOdometry(size_t from, size_t to, const mrpt::math::TPose2D& increment,
                     const Eigen::Matrix3d& cov, size_t scale);
    /// An odometry increment u scaled by s = (s_d, s_θ): (s_d u_x, s_d u_y, s_θ u_θ).
    static mrpt::math::TPose2D scaled(const mrpt::math::TPose2D& u, const Eigen::Vector2d& s)
    {
        return {s[0] * u.x, s[0] * u.y, s[1] * u.phi};
    }
    /// `z`: the point as seen from `pose`, in its frame; `cov` its 2×2 covariance.
    void addPointReading(size_t pose, size_t point, const Eigen::Vector2d& z,
                         const Eigen::Matrix2d& cov);
    /// The position of pose `seen` (another robot) as seen from `pose`, in its frame.
    void addPoseReading(size_t pose, size_t seen, const Eigen::Vector2d& z,
                        const Eigen::Matrix2d& cov);

    struct TOptions {
        size_t max_iterations = 30;
        /// [σ] Huber threshold on a reading's whitened residual norm (≤ 0: plain least squares)
        double huber_threshold = 3;
        /// stop when the cost falls by less than this fraction in an iteration
        double relative_tolerance = 1e-6;
    };
    struct TResult {
        double initial_cost = 0, final_cost = 0;  ///< Σ ρ(‖e‖²) over the factors
        size_t iterations = 0;
        size_t readings = 0;  ///< reading factors (of points and of poses)
        /// readings whose final whitened residual exceeds the Huber threshold
        size_t outlier_readings = 0;
    };
    /// \throw std::invalid_argument without a prior, with a pose without prior or odometry or
    /// a point without readings; std::runtime_error if the normal equations cannot be solved.
    TResult optimize(const TOptions& options);

    /// Σ ρ(‖e‖²) at the current values (ρ: identity for priors and odometry, Huber for readings).
    double cost(double huber_threshold) const;

    const mrpt::math::TPose2D& pose(size_t i) const { return m_poses[i]; }
    const Eigen::Vector2d& point(size_t j) const { return m_points[j]; }
    size_t poseCount() const { return m_poses.size(); }
    size_t pointCount() const { return m_points.size(); }
    const Eigen::Vector2d& odometryScale(size_t s) const { return m_scales[s]; }

  private:
    struct TPrior {
        size_t pose;
        mrpt::math::TPose2D mean;
        Eigen::Matrix3d sqrt_info;  ///< Lᵀ with Lᵀ L = Σ⁻¹: e = Lᵀ r
    };
    struct TOdometry {
        size_t from, to;
        mrpt::math::TPose2D increment;
        Eigen::Matrix3d sqrt_info;
        std::optional<size_t> scale;
    };
    struct TScalePrior {
        size_t scale;
        Eigen::Vector2d mean;
        Eigen::Matrix2d sqrt_info;
    };
    struct TReading {
        size_t pose, target;  ///< target: a point, or a pose when of_pose
        bool of_pose;
        Eigen::Vector2d z;
        Eigen::Matrix2d sqrt_info;
    };
    std::vector<mrpt::math::TPose2D> m_poses;
    std::vector<Eigen::Vector2d> m_points;
    std::vector<Eigen::Vector2d> m_scales;
    std::vector<TScalePrior> m_scalePriors;
    std::vector<TPrior> m_priors;
    std::vector<TOdometry> m_odometry;
    std::vector<TReading> m_readings;

    double m_huber = 0;  ///< threshold of the current optimize()

    Eigen::Vector3d priorError(const TPrior& f) const;  ///< whitened residuals
    Eigen::Vector3d odometryError(const TOdometry& f) const;
    Eigen::Vector2d readingError(const TReading& f) const;
    Eigen::Vector2d targetOf(const TReading& r) const;
    TResult finish(TResult result) const;  ///< counts the outlier readings
    size_t pointOffset(size_t j) const { return 3 * m_poses.size() + 2 * j; }
    size_t scaleOffset(size_t s) const { return pointOffset(m_points.size()) + 2 * s; }
    /// The increment of an odometry factor, scaled if it has a scale variable.
    mrpt::math::TPose2D scaledIncrement(const TOdometry& f) const;
};

}  // namespace mrpt_vslam::multirobot
