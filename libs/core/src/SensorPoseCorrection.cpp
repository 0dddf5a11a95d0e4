#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt_vslam/core/SensorPoseCorrection.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

namespace mrpt_vslam::core {

namespace {

Eigen::Matrix2d rotation(double a)
{
    Eigen::Matrix2d R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    return R;
}

/// r(x), its Jacobian ∂r/∂x and its covariance, of one pair (N = 2) or bearing (N = 1).
template <int N>
struct TLinearized {
    Eigen::Matrix<double, N, 1> r;
    Eigen::Matrix<double, N, 3> J;
    Eigen::Matrix<double, N, N> C;

    /// The whitened residual e and Jacobian: L e = r, L Je = J with C = L Lᵀ.
    std::pair<Eigen::Matrix<double, N, 1>, Eigen::Matrix<double, N, 3>> whitened() const
    {
        const Eigen::Matrix<double, N, N> L = C.llt().matrixL();
        return {L.template triangularView<Eigen::Lower>().solve(r),
                L.template triangularView<Eigen::Lower>().solve(J)};
    }
};

// d R(a)/da = R(a) S = S R(a)
const Eigen::Matrix2d S = (Eigen::Matrix2d() << 0, -1, 1, 0).finished();

/// A pair's linearization, with its covariance C = A + B Q Bᵀ in two parts: that of its
/// readings (A) and the odometry's Jacobian (B).
struct TPairLinearized : TLinearized<2> {
    Eigen::Matrix2d A;
    Eigen::Matrix<double, 2, 3> B;
};

TPairLinearized linearize(const TReadingPair& p, const Eigen::Vector3d& x)
{
    const Eigen::Vector2d t = x.head<2>(), tu(p.u.x, p.u.y);
    const Eigen::Matrix2d Rd = rotation(x[2]), Ru = rotation(p.u.phi);
    const Eigen::Vector2d pj = Rd * p.z_j + t;  // the point in x_j's frame
    TPairLinearized l;
    l.r = Rd * p.z_i + t - (Ru * pj + tu);
    l.J.leftCols<2>() = Eigen::Matrix2d::Identity() - Ru;
    // ∂r/∂θ = S (R(θ) z_i − Ru R(θ) z_j) is S (tu − (I − Ru) t) plus S r: the readings' noise,
    // which would count as information on θ; the expected Jacobian leaves it out
    l.J.col(2) = S * (tu - l.J.leftCols<2>() * t);
    // ∂(u ⊕ pj)/∂u = [I, S Ru pj]
    l.B.leftCols<2>().setIdentity();
    l.B.col(2) = S * Ru * pj;
    l.A = Rd * p.R_i * Rd.transpose() + Ru * Rd * p.R_j * Rd.transpose() * Ru.transpose();
    l.C = l.A + l.B * p.Q * l.B.transpose();
    return l;
}

TLinearized<1> linearize(const TEarlierPoseBearing& b, const Eigen::Vector3d& x)
{
    const Eigen::Vector2d tu(b.u.x, b.u.y);
    const Eigen::Matrix2d Rd = rotation(x[2]), RuT = rotation(-b.u.phi);
    const Eigen::Vector2d c = Rd * b.sensor + x.head<2>();  // the sensor in the robot frame
    const Eigen::Vector2d p = RuT * (c - tu);               // c at x_i, in x_j's frame
    const Eigen::Vector2d v = p - c;
    // ∂atan2(v)/∂v
    const Eigen::RowVector2d a = Eigen::RowVector2d(-v.y(), v.x()) / v.squaredNorm();
    TLinearized<1> l;
    l.r[0] = mrpt::math::wrapToPi(std::atan2(v.y(), v.x()) - x[2] - b.bearing);
    // ∂v/∂t = Ruᵀ − I, ∂v/∂θ = (Ruᵀ − I) S R(θ) s
    const Eigen::Matrix2d dv = RuT - Eigen::Matrix2d::Identity();
    l.J.leftCols<2>() = a * dv;
    l.J(0, 2) = a * dv * S * Rd * b.sensor - 1;
    // ∂p/∂u = [−Ruᵀ, −S p]
    Eigen::Matrix<double, 2, 3> Ju;
    Ju.leftCols<2>() = -RuT;
    Ju.col(2) = -S * p;
    l.C(0, 0) = b.var + (a * Ju * b.Q * Ju.transpose() * a.transpose())(0, 0);
    return l;
}

}  // namespace

std::pair<mrpt::math::TPose2D, Eigen::Matrix3d> composedOdometry(
    const std::function<const TOdometryGaussian&(size_t)>& motion, size_t from, size_t to)
{
    mrpt::poses::CPosePDFGaussian u;
    for (size_t s = from + 1; s <= to; s++) {
        const TOdometryGaussian& step = motion(s);
        u += mrpt::poses::CPosePDFGaussian(mrpt::poses::CPose2D(step.mean),
                                           mrpt::math::CMatrixDouble33(step.cov));
    }
    return {u.mean.asTPose(), u.cov.asEigen()};
}

Eigen::Vector2d TSensorPoseCorrection::whitenedResidual(const TReadingPair& p) const
{
    return linearize(p, delta).whitened().first;
}

double TSensorPoseCorrection::whitenedResidual(const TEarlierPoseBearing& b) const
{
    return linearize(b, delta).whitened().first[0];
}

double TSensorPoseCorrection::turnConfounding() const { return cov(2, 2) * cov.inverse()(2, 2); }

double TSensorPoseCorrection::largestMoveStd() const
{
    const double a = cov(0, 0), b = cov(0, 1), c = cov(1, 1);
    return std::sqrt((a + c) / 2 + std::hypot((a - c) / 2, b));
}

TSensorPoseCorrection TSensorPoseCorrection::estimate(
    const std::vector<TReadingPair>& pairs, const std::vector<TEarlierPoseBearing>& bearings,
    double huber)
{
    const Eigen::Vector3d priorInfo(1.0, 1.0, 1.0 / (M_PI * M_PI));
    const auto rho = [&](double n) {
        return huber > 0 && n > huber ? 2 * huber * n - huber * huber : n * n;
    };
    // Σ ρ(‖e‖²) plus the prior's, at `c`
    const auto cost = [&](const TSensorPoseCorrection& c) {
        double sum = c.delta.dot(priorInfo.cwiseProduct(c.delta));
        for (const auto& p : pairs) sum += rho(c.whitenedResidual(p).norm());
        for (const auto& b : bearings) sum += rho(std::abs(c.whitenedResidual(b)));
        return sum;
    };
    const auto weight = [&](double norm) {  // IRLS
        return huber > 0 && norm > huber ? huber / norm : 1.0;
    };
    // the pairs by their two steps (a pair without them, step_j <= step_i, alone)
    std::map<std::pair<size_t, size_t>, std::vector<size_t>> bySteps;
    std::vector<std::vector<size_t>> groups;
    for (size_t i = 0; i < pairs.size(); i++) {
        if (pairs[i].step_j > pairs[i].step_i)
            bySteps[{pairs[i].step_i, pairs[i].step_j}].push_back(i);
        else
            groups.push_back({i});
    }
    for (auto& [steps, members] : bySteps) groups.push_back(std::move(members));
    // from four turns: a sensor mounted a quarter or half turn off is found too
    std::optional<TSensorPoseCorrection> best;
    double bestCost = 0;
    for (const double start : {0.0, M_PI / 2, M_PI, -M_PI / 2}) {
        TSensorPoseCorrection c;
        c.pairs = pairs.size() + bearings.size();
        c.delta[2] = start;
        Eigen::Matrix3d H;
        for (int iteration = 0; iteration < 20; iteration++) {
            H = priorInfo.asDiagonal();
            Eigen::Vector3d g = priorInfo.cwiseProduct(c.delta);
            const auto add = [&](const auto& l) {
                const auto [e, Je] = l.whitened();
                const double w = weight(e.norm());
                H += w * Je.transpose() * Je;
                g += w * Je.transpose() * e;
            };
            // A group's residuals r_p = (readings' part, covariance A_p) − B_p η share one
            // odometry error η ~ N(0, Q): its information is Σ J_pᵀ W_p J_p less
            // Gᵀ Q (I + K Q)⁻¹ G (Woodbury), W_p = w_p A_p⁻¹, K = Σ B_pᵀ W_p B_p,
            // G = Σ B_pᵀ W_p J_p; likewise its gradient. A pair alone (w = 1): (A + B Q Bᵀ)⁻¹.
            for (const auto& group : groups) {
                Eigen::Matrix3d K = Eigen::Matrix3d::Zero(), G = Eigen::Matrix3d::Zero();
                Eigen::Vector3d Gr = Eigen::Vector3d::Zero();
                for (const size_t i : group) {
                    const TPairLinearized l = linearize(pairs[i], c.delta);
                    const Eigen::Matrix2d W = weight(l.whitened().first.norm()) * l.A.inverse();
                    H += l.J.transpose() * W * l.J;
                    g += l.J.transpose() * W * l.r;
                    K += l.B.transpose() * W * l.B;
                    G += l.B.transpose() * W * l.J;
                    Gr += l.B.transpose() * W * l.r;
                }
                const Eigen::Matrix3d& Q = pairs[group.front()].Q;
                const Eigen::Matrix3d N =
                    Q * (Eigen::Matrix3d::Identity() + K * Q).partialPivLu().inverse();
                H -= G.transpose() * N * G;
                g -= G.transpose() * N * Gr;
            }
            for (const auto& b : bearings) add(linearize(b, c.delta));
            const Eigen::Vector3d step = -H.ldlt().solve(g);
            c.delta += step;
            if (step.cwiseAbs().maxCoeff() < 1e-9) break;
        }
        c.delta[2] = mrpt::math::wrapToPi(c.delta[2]);
        c.cov = H.inverse();
        const double f = cost(c);
        if (best && f >= bestCost) continue;
        best = c;
        bestCost = f;
    }
    if (huber > 0) {
        for (const auto& p : pairs) best->outlier_pairs += best->whitenedResidual(p).norm() > huber;
        for (const auto& b : bearings)
            best->outlier_pairs += std::abs(best->whitenedResidual(b)) > huber;
    }
    return *best;
}

}  // namespace mrpt_vslam::core
