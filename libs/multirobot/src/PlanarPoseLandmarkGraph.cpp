#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/multirobot/PlanarPoseLandmarkGraph.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::multirobot {

using mrpt::math::TPose2D;
using mrpt::math::wrapToPi;

namespace {

template <int N>
Eigen::Matrix<double, N, N> sqrtInformation(const Eigen::Matrix<double, N, N>& cov)
{
    if (!cov.allFinite() || Eigen::LLT<Eigen::Matrix<double, N, N>>(cov).info() != Eigen::Success)
        throw std::invalid_argument("PlanarPoseLandmarkGraph: covariance not positive definite");
    return Eigen::LLT<Eigen::Matrix<double, N, N>>(cov.inverse()).matrixU();  // Uᵀ U = Σ⁻¹
}

/// ρ(s) of a squared whitened residual s, and the IRLS weight ρ'(s).
std::pair<double, double> huber(double s, double k)
{
    if (k <= 0 || s <= k * k) return {s, 1.0};
    const double n = std::sqrt(s);
    return {2 * k * n - k * k, k / n};
}

/// R(θ)ᵀ and its derivative in θ.
Eigen::Matrix2d rotationT(double phi)
{
    const double c = std::cos(phi), s = std::sin(phi);
    return (Eigen::Matrix2d() << c, s, -s, c).finished();
}
Eigen::Matrix2d rotationTDerivative(double phi)
{
    const double c = std::cos(phi), s = std::sin(phi);
    return (Eigen::Matrix2d() << -s, c, -c, -s).finished();
}

}  // namespace

size_t PlanarPoseLandmarkGraph::addPose(const TPose2D& initial)
{
    m_poses.push_back(initial);
    return m_poses.size() - 1;
}

size_t PlanarPoseLandmarkGraph::addPoint(const Eigen::Vector2d& initial)
{
    m_points.push_back(initial);
    return m_points.size() - 1;
}

size_t PlanarPoseLandmarkGraph::addOdometryScale(const Eigen::Vector2d& initial,
                                                 const Eigen::Vector2d& mean,
                                                 const Eigen::Matrix2d& cov)
{
    m_scales.push_back(initial);
    m_scalePriors.push_back({m_scales.size() - 1, mean, sqrtInformation<2>(cov)});
    return m_scales.size() - 1;
}

void PlanarPoseLandmarkGraph::addPosePrior(size_t pose, const TPose2D& mean,
                                           const Eigen::Matrix3d& cov)
{
    m_priors.push_back({pose, mean, sqrtInformation<3>(cov)});
}

void PlanarPoseLandmarkGraph::addOdometry(size_t from, size_t to, const TPose2D& increment,
                                          const Eigen::Matrix3d& cov)
{
    m_odometry.push_back({from, to, increment, sqrtInformation<3>(cov), std::nullopt});
}

void PlanarPoseLandmarkGraph::addOdometry(size_t from, size_t to, const TPose2D& increment,
                                          const Eigen::Matrix3d& cov, size_t scale)
{
    m_odometry.push_back({from, to, increment, sqrtInformation<3>(cov), scale});
}

TPose2D PlanarPoseLandmarkGraph::scaledIncrement(const TOdometry& f) const
{
    return f.scale ? scaled(f.increment, m_scales[*f.scale]) : f.increment;
}

void PlanarPoseLandmarkGraph::addPointReading(size_t pose, size_t point, const Eigen::Vector2d& z,
                                              const Eigen::Matrix2d& cov)
{
    m_readings.push_back({pose, point, false, z, sqrtInformation<2>(cov)});
}

void PlanarPoseLandmarkGraph::addPoseReading(size_t pose, size_t seen, const Eigen::Vector2d& z,
                                             const Eigen::Matrix2d& cov)
{
    m_readings.push_back({pose, seen, true, z, sqrtInformation<2>(cov)});
}

Eigen::Vector2d PlanarPoseLandmarkGraph::targetOf(const TReading& r) const
{
    if (!r.of_pose) return m_points[r.target];
    return {m_poses[r.target].x, m_poses[r.target].y};
}

Eigen::Vector3d PlanarPoseLandmarkGraph::priorError(const TPrior& f) const
{
    const TPose2D& x = m_poses[f.pose];
    return f.sqrt_info *
           Eigen::Vector3d(x.x - f.mean.x, x.y - f.mean.y, wrapToPi(x.phi - f.mean.phi));
}

Eigen::Vector3d PlanarPoseLandmarkGraph::odometryError(const TOdometry& f) const
{
    const TPose2D &a = m_poses[f.from], &b = m_poses[f.to];
    const TPose2D u = scaledIncrement(f);
    const Eigen::Vector2d d = rotationT(a.phi) * Eigen::Vector2d(b.x - a.x, b.y - a.y);
    return f.sqrt_info * Eigen::Vector3d(d.x() - u.x, d.y() - u.y, wrapToPi(b.phi - a.phi - u.phi));
}

Eigen::Vector2d PlanarPoseLandmarkGraph::readingError(const TReading& f) const
{
    const TPose2D& x = m_poses[f.pose];
    return f.sqrt_info * (rotationT(x.phi) * (targetOf(f) - Eigen::Vector2d(x.x, x.y)) - f.z);
}

double PlanarPoseLandmarkGraph::cost(double huber_threshold) const
{
    double c = 0;
    for (const auto& f : m_priors) c += priorError(f).squaredNorm();
    for (const auto& f : m_odometry) c += odometryError(f).squaredNorm();
    for (const auto& f : m_scalePriors)
        c += (f.sqrt_info * (m_scales[f.scale] - f.mean)).squaredNorm();
    for (const auto& f : m_readings)
        c += huber(readingError(f).squaredNorm(), huber_threshold).first;
    return c;
}

PlanarPoseLandmarkGraph::TResult PlanarPoseLandmarkGraph::optimize(const TOptions& options)
{
    const auto n = static_cast<Eigen::Index>(scaleOffset(m_scales.size()));
    std::vector<Eigen::Triplet<double>> triplets;  // the entries of each factor's blocks
    triplets.reserve(9 * m_priors.size() + 64 * m_odometry.size() + 4 * m_scalePriors.size() +
                     25 * m_readings.size());
    Eigen::VectorXd b(n);
    // adds Jᵀ w J and Jᵀ w e of one whitened factor e = J δ + e0 over the blocks `at`
    auto accumulate = [&](const auto& J, const auto& e, const auto& at, double w) {
        const auto H = (w * J.transpose() * J).eval();
        const auto g = (w * J.transpose() * e).eval();
        for (size_t bi = 0, ci = 0; bi < at.size(); ci += at[bi].second, bi++)
            for (size_t bj = 0, cj = 0; bj < at.size(); cj += at[bj].second, bj++)
                for (int i = 0; i < at[bi].second; i++)
                    for (int j = 0; j < at[bj].second; j++)
                        triplets.emplace_back(at[bi].first + i, at[bj].first + j,
                                              H(ci + i, cj + j));
        for (size_t bi = 0, ci = 0; bi < at.size(); ci += at[bi].second, bi++)
            b.segment(at[bi].first, at[bi].second) += g.segment(ci, at[bi].second);
    };
    using Blocks = std::vector<std::pair<Eigen::Index, int>>;
    auto poseAt = [](size_t i) { return std::pair<Eigen::Index, int>(3 * i, 3); };

    auto linearize = [&]() {
        triplets.clear();
        b.setZero();
        for (const auto& f : m_priors)
            accumulate(f.sqrt_info, priorError(f), Blocks{poseAt(f.pose)}, 1.0);
        for (const auto& f : m_odometry) {
            const TPose2D &a = m_poses[f.from], &c = m_poses[f.to];
            const Eigen::Vector2d dt(c.x - a.x, c.y - a.y);  // Jacobian of odometryError()
            Eigen::Matrix<double, 3, 6> J = Eigen::Matrix<double, 3, 6>::Zero();
            J.block<2, 2>(0, 0) = -rotationT(a.phi);
            J.block<2, 1>(0, 2) = rotationTDerivative(a.phi) * dt;
            J(2, 2) = -1;
            J.block<2, 2>(0, 3) = rotationT(a.phi);
            J(2, 5) = 1;
            if (!f.scale) {
                accumulate((f.sqrt_info * J).eval(), odometryError(f),
                           Blocks{poseAt(f.from), poseAt(f.to)}, 1.0);
                continue;
            }
            Eigen::Matrix<double, 3, 8> Js = Eigen::Matrix<double, 3, 8>::Zero();
            Js.leftCols<6>() = J;
            Js.block<2, 1>(0, 6) = -Eigen::Vector2d(f.increment.x, f.increment.y);
            Js(2, 7) = -f.increment.phi;
            accumulate((f.sqrt_info * Js).eval(), odometryError(f),
                       Blocks{poseAt(f.from), poseAt(f.to), {scaleOffset(*f.scale), 2}}, 1.0);
        }
        for (const auto& f : m_scalePriors)
            accumulate(f.sqrt_info, (f.sqrt_info * (m_scales[f.scale] - f.mean)).eval(),
                       Blocks{{scaleOffset(f.scale), 2}}, 1.0);
        for (const auto& f : m_readings) {
            const TPose2D& x = m_poses[f.pose];
            const Eigen::Vector2d dt = targetOf(f) - Eigen::Vector2d(x.x, x.y);
            Eigen::Matrix<double, 2, 5> J;
            J.block<2, 2>(0, 0) = -rotationT(x.phi);
            J.block<2, 1>(0, 2) = rotationTDerivative(x.phi) * dt;
            J.block<2, 2>(0, 3) = rotationT(x.phi);
            const Eigen::Vector2d e = readingError(f);
            const double w = huber(e.squaredNorm(), m_huber).second;
            // the target: another pose's position, or a point
            const Eigen::Index target = f.of_pose ? 3 * f.target : pointOffset(f.target);
            const Blocks at{poseAt(f.pose), {target, 2}};
            accumulate((f.sqrt_info * J).eval(), e, at, w);
        }
    };
    auto step = [&](const Eigen::VectorXd& d, double scale) {
        for (size_t i = 0; i < m_poses.size(); i++) {
            m_poses[i].x += scale * d[3 * i];
            m_poses[i].y += scale * d[3 * i + 1];
            m_poses[i].phi = wrapToPi(m_poses[i].phi + scale * d[3 * i + 2]);
        }
        for (size_t j = 0; j < m_points.size(); j++)
            m_points[j] += scale * d.segment<2>(pointOffset(j));
        for (size_t j = 0; j < m_scales.size(); j++)
            m_scales[j] += scale * d.segment<2>(scaleOffset(j));
    };

    std::vector<bool> pose_tied(m_poses.size(), false), point_seen(m_points.size(), false);
    for (const auto& f : m_priors) pose_tied[f.pose] = true;
    for (const auto& f : m_odometry) pose_tied[f.from] = pose_tied[f.to] = true;
    for (const auto& f : m_readings)
        if (!f.of_pose) point_seen[f.target] = true;
    if (m_priors.empty() || std::count(pose_tied.begin(), pose_tied.end(), false) ||
        std::count(point_seen.begin(), point_seen.end(), false))
        throw std::invalid_argument(
            "PlanarPoseLandmarkGraph: needs a prior, a prior or odometry at every pose and a "
            "reading of every point");
    m_huber = options.huber_threshold;
    TResult result;
    result.initial_cost = result.final_cost = cost(m_huber);
    double lambda = 1e-4;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
    Eigen::SparseMatrix<double> H(n, n);
    bool pattern_known = false;
    for (; result.iterations < options.max_iterations; result.iterations++) {
        linearize();
        H.setFromTriplets(triplets.begin(), triplets.end());
        const Eigen::VectorXd diagonal = H.diagonal();
        bool improved = false;
        for (int attempt = 0; attempt < 10 && !improved; attempt++) {
            Eigen::SparseMatrix<double> damped = H;
            for (Eigen::Index i = 0; i < n; i++)
                damped.coeffRef(i, i) += lambda * std::max(diagonal[i], 1e-9);
            if (!pattern_known) solver.analyzePattern(damped);
            pattern_known = true;
            solver.factorize(damped);
            if (solver.info() != Eigen::Success)
                throw std::runtime_error(
                    "PlanarPoseLandmarkGraph: normal equations not solvable (an unconstrained "
                    "pose or point?)");
            const Eigen::VectorXd d = solver.solve(-b);
            step(d, 1.0);
            const double c = cost(m_huber);
            if (c < result.final_cost) {
                improved = true;
                const double fall = (result.final_cost - c) / std::max(result.final_cost, 1e-300);
                result.final_cost = c;
                lambda = std::max(lambda / 10, 1e-9);
                if (fall < options.relative_tolerance) {
                    result.iterations++;
                    return finish(result);
                }
            } else {
                step(d, -1.0);
                lambda *= 10;
            }
        }
        if (!improved) break;
    }
    return finish(result);
}

PlanarPoseLandmarkGraph::TResult PlanarPoseLandmarkGraph::finish(TResult result) const
{
    result.readings = m_readings.size();
    for (const auto& f : m_readings)
        if (m_huber > 0 && readingError(f).squaredNorm() > m_huber * m_huber)
            result.outlier_readings++;
    return result;
}

}  // namespace mrpt_vslam::multirobot
