#include <mrpt/core/format.h>
#include <mrpt/math/distributions.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/core/TrajectoryMetrics.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mrpt_vslam::core {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Mean, RMSE and max of |v|; NaN for an empty series.
void summarize(const std::vector<double>& v, double& rmse, double& mean, double& max)
{
    if (v.empty()) {
        rmse = mean = max = kNaN;
        return;
    }
    double sum = 0, sumSq = 0;
    max = 0;
    for (double x : v) {
        sum += std::abs(x);
        sumSq += x * x;
        max = std::max(max, std::abs(x));
    }
    mean = sum / v.size();
    rmse = std::sqrt(sumSq / v.size());
}

}  // namespace

std::vector<std::pair<size_t, size_t>> associateByTime(const TumTrajectory& estimate,
                                                       const TumTrajectory& ground_truth,
                                                       double tolerance)
{
    std::vector<std::pair<size_t, size_t>> pairs;
    for (size_t i = 0; i < estimate.size(); i++) {
        const int j = ground_truth.nearestIndex(estimate.timestamps[i], tolerance);
        if (j >= 0) pairs.emplace_back(i, static_cast<size_t>(j));
    }
    return pairs;
}

mrpt::math::TPose2D alignSE2(const std::vector<mrpt::math::TPoint2D>& a,
                             const std::vector<mrpt::math::TPoint2D>& b)
{
    if (a.size() != b.size() || a.size() < 2)
        throw std::invalid_argument("alignSE2: need two equally long lists of at least 2 points");
    mrpt::math::TPoint2D ca{0, 0}, cb{0, 0};
    for (size_t i = 0; i < a.size(); i++) {
        ca += a[i];
        cb += b[i];
    }
    ca *= 1.0 / a.size();
    cb *= 1.0 / b.size();
    // θ = atan2(Σ a'×b', Σ a'·b') over the centred points a' = a - ca, b' = b - cb.
    double sumCross = 0, sumDot = 0;
    for (size_t i = 0; i < a.size(); i++) {
        const auto da = a[i] - ca, db = b[i] - cb;
        sumCross += da.x * db.y - da.y * db.x;
        sumDot += da.x * db.x + da.y * db.y;
    }
    const double th = std::atan2(sumCross, sumDot);
    // t = cb - R(θ) ca
    const double c = std::cos(th), s = std::sin(th);
    return {cb.x - (c * ca.x - s * ca.y), cb.y - (s * ca.x + c * ca.y), th};
}

mrpt::math::TPose3D applySE2(const mrpt::math::TPose2D& t, const mrpt::math::TPose3D& p)
{
    const double c = std::cos(t.phi), s = std::sin(t.phi);
    return {t.x + c * p.x - s * p.y,
            t.y + s * p.x + c * p.y,
            p.z,
            mrpt::math::wrapToPi(p.yaw + t.phi),
            p.pitch,
            p.roll};
}

TTrajectoryMetrics evaluateTrajectory(const TumTrajectory& estimate,
                                      const TumTrajectory& ground_truth,
                                      const TTrajectoryMetricsOptions& options)
{
    TumTrajectory later;  // the estimate after options.after
    for (size_t i = 0; i < estimate.size(); i++)
        if (estimate.timestamps[i] > options.after)
            later.push_back(estimate.timestamps[i], estimate.poses[i]);
    if (later.empty())
        throw std::runtime_error(
            std::isfinite(options.after)
                ? mrpt::format("no estimated pose after t = %.3f s", options.after)
                : std::string("no estimated pose"));
    const auto pairs = associateByTime(later, ground_truth, options.time_tolerance);
    if (pairs.empty() ||
        static_cast<double>(pairs.size()) < options.min_matched_share * later.size())
        throw std::runtime_error(mrpt::format(
            "%zu of %zu estimated poses have a ground-truth pose within %g s (at least %.0f %% "
            "must): the estimate and the ground truth hardly overlap in time",
            pairs.size(), later.size(), options.time_tolerance, 100 * options.min_matched_share));
    TTrajectoryMetrics m;
    m.estimate_poses = later.size();
    m.ground_truth_poses = ground_truth.size();
    if (options.align_se2 && pairs.size() >= 2) {
        std::vector<mrpt::math::TPoint2D> a, b;
        for (const auto& [i, j] : pairs) {
            a.emplace_back(later.poses[i].x, later.poses[i].y);
            b.emplace_back(ground_truth.poses[j].x, ground_truth.poses[j].y);
        }
        m.alignment = alignSE2(a, b);
    }
    size_t under = 0;
    for (const auto& [i, j] : pairs) {
        const auto est = applySE2(m.alignment, later.poses[i]);
        const auto& gt = ground_truth.poses[j];
        const double dx = est.x - gt.x, dy = est.y - gt.y, dz = est.z - gt.z;
        const double dYaw = mrpt::math::wrapToPi(est.yaw - gt.yaw);
        m.timestamps.push_back(later.timestamps[i]);
        m.position_errors.push_back(std::sqrt(dx * dx + dy * dy + dz * dz));
        m.heading_errors.push_back(dYaw);
        if (std::abs(dYaw) <= options.heading_threshold) under++;
    }
    summarize(m.position_errors, m.ate_rmse, m.ate_mean, m.ate_max);
    summarize(m.heading_errors, m.heading_rmse, m.heading_mean, m.heading_max);
    m.heading_share_under_threshold = static_cast<double>(under) / pairs.size();
    return m;
}

double nees(const Eigen::VectorXd& error, const Eigen::MatrixXd& cov)
{
    if (cov.rows() != error.size() || cov.cols() != error.size())
        throw std::invalid_argument("nees: covariance size does not match the error size");
    const Eigen::LLT<Eigen::MatrixXd> llt(cov);
    if (llt.info() != Eigen::Success)
        throw std::invalid_argument("nees: covariance is not positive definite");
    // e^T P^-1 e = |L^-1 e|² with P = L L^T
    return llt.matrixL().solve(error).squaredNorm();
}

double poseNEES(const mrpt::math::TPose2D& estimate, const mrpt::math::TPose2D& truth,
                const Eigen::Matrix3d& cov)
{
    Eigen::Vector3d e(estimate.x - truth.x, estimate.y - truth.y,
                      mrpt::math::wrapToPi(estimate.phi - truth.phi));
    return nees(e, cov);
}

double poseNEES(const mrpt::math::TPose3D& estimate, const mrpt::math::TPose3D& truth,
                const Eigen::Matrix<double, 6, 6>& cov)
{
    Eigen::Matrix<double, 6, 1> e;
    e << estimate.x - truth.x, estimate.y - truth.y, estimate.z - truth.z,
        mrpt::math::wrapToPi(estimate.yaw - truth.yaw),
        mrpt::math::wrapToPi(estimate.pitch - truth.pitch),
        mrpt::math::wrapToPi(estimate.roll - truth.roll);
    return nees(e, cov);
}

std::pair<double, double> chi2Bounds(unsigned int dof, double confidence, unsigned int runs)
{
    if (dof == 0 || runs == 0 || !(confidence > 0 && confidence < 1))
        throw std::invalid_argument("chi2Bounds: need dof > 0, runs > 0 and 0 < confidence < 1");
    const double alpha = 1 - confidence;
    const unsigned int n = dof * runs;
    // chi2inv() is the Wilson-Hilferty approximation, which may go below 0 for tiny dof.
    const double lower = std::max(0.0, mrpt::math::chi2inv(alpha / 2, n));
    return {lower / runs, mrpt::math::chi2inv(1 - alpha / 2, n) / runs};
}

}  // namespace mrpt_vslam::core
