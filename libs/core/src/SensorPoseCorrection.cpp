#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt_vslam/core/SensorPoseCorrection.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <cmath>
#include <limits>
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

/// The unknowns x = (t_x, t_y, θ, k).
using TUnknowns = Eigen::Matrix<double, 4, 1>;

/// r(x), its Jacobian ∂r/∂x and its covariance, of one pair (N = 2) or bearing (N = 1).
template <int N>
struct TLinearized {
    Eigen::Matrix<double, N, 1> r;
    Eigen::Matrix<double, N, 4> J;
    Eigen::Matrix<double, N, N> C;

    /// The whitened residual e and Jacobian: L e = r, L Je = J with C = L Lᵀ.
    std::pair<Eigen::Matrix<double, N, 1>, Eigen::Matrix<double, N, 4>> whitened() const
    {
        const Eigen::Matrix<double, N, N> L = C.llt().matrixL();
        return {L.template triangularView<Eigen::Lower>().solve(r),
                L.template triangularView<Eigen::Lower>().solve(J)};
    }
};

// d R(a)/da = R(a) S = S R(a)
const Eigen::Matrix2d S = (Eigen::Matrix2d() << 0, -1, 1, 0).finished();

/// A pair's linearization, with its covariance C = A + B Q Bᵀ in two parts: that of its
/// readings (A) and the odometry's Jacobian (B), and what the gradient needs: ∂r/∂k itself and
/// ∂b/∂x, b B's θ column (the others do not depend on x).
struct TPairLinearized : TLinearized<2> {
    Eigen::Matrix2d A;
    Eigen::Matrix<double, 2, 3> B;
    Eigen::Vector2d dr_dk;
    Eigen::Matrix<double, 2, 4> dB;
};

TPairLinearized linearize(const TReadingPair& p, const TUnknowns& x)
{
    const Eigen::Vector2d t = x.head<2>(), tu(p.u.x, p.u.y);
    const double k = x[3];
    const Eigen::Matrix2d Rd = rotation(x[2]), Ru = rotation(p.u.phi);
    const Eigen::Vector2d pj = k * Rd * p.z_j + t;  // the point in x_j's frame
    TPairLinearized l;
    l.r = k * Rd * p.z_i + t - (Ru * pj + tu);
    l.J.leftCols<2>() = Eigen::Matrix2d::Identity() - Ru;
    // ∂r/∂θ = k S (R(θ) z_i − Ru R(θ) z_j) is S v plus S r, with v = tu − (I − Ru) t; S r, the
    // readings' noise, would count as information on θ: the expected Jacobian leaves it out.
    // Likewise ∂r/∂k is v / k (along v, where θ's is across it) in the information; the
    // gradient takes k's own (estimate(): errors in variables).
    const Eigen::Vector2d v = tu - l.J.leftCols<2>() * t;
    l.J.col(2) = S * v;
    l.J.col(3) = v / k;
    // ∂(u ⊕ pj)/∂u = [I, S Ru pj]
    l.B.leftCols<2>().setIdentity();
    l.B.col(2) = S * Ru * pj;
    l.dr_dk = Rd * p.z_i - Ru * Rd * p.z_j;
    l.dB.leftCols<2>() = S * Ru;
    l.dB.col(2) = S * Ru * S * (pj - t);
    l.dB.col(3) = S * Ru * Rd * p.z_j;
    l.A = k * k * (Rd * p.R_i * Rd.transpose() + Ru * Rd * p.R_j * Rd.transpose() * Ru.transpose());
    l.C = l.A + l.B * p.Q * l.B.transpose();
    return l;
}

TLinearized<1> linearize(const TEarlierPoseBearing& b, const TUnknowns& x)
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
    l.J(0, 3) = 0;
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
    return linearize(p, TUnknowns(delta[0], delta[1], delta[2], scale)).whitened().first;
}

double TSensorPoseCorrection::whitenedResidual(const TEarlierPoseBearing& b) const
{
    return linearize(b, TUnknowns(delta[0], delta[1], delta[2], scale)).whitened().first[0];
}

double TSensorPoseCorrection::turnConfounding() const { return cov(2, 2) * cov.inverse()(2, 2); }

double TSensorPoseCorrection::largestMoveStd() const
{
    const double a = cov(0, 0), b = cov(0, 1), c = cov(1, 1);
    return std::sqrt((a + c) / 2 + std::hypot((a - c) / 2, b));
}

TSensorPoseCorrection TSensorPoseCorrection::estimate(
    const std::vector<TReadingPair>& pairs, const std::vector<TEarlierPoseBearing>& bearings,
    double huber, bool fit_scale)
{
    bool holdScale = !fit_scale;
    const TUnknowns priorMean(0, 0, 0, 1), priorInfo(1.0, 1.0, 1.0 / (M_PI * M_PI), 1.0);
    const auto rho = [&](double n) {
        return huber > 0 && n > huber ? 2 * huber * n - huber * huber : n * n;
    };
    // Σ ρ(‖e‖²) plus the prior's, at `c`
    const auto cost = [&](const TSensorPoseCorrection& c) {
        const TUnknowns d = TUnknowns(c.delta[0], c.delta[1], c.delta[2], c.scale) - priorMean;
        double sum = d.dot(priorInfo.cwiseProduct(d));
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
    using Matrix34 = Eigen::Matrix<double, 3, 4>;
    using Matrix4 = Eigen::Matrix<double, 4, 4>;
    // An iterate's IRLS weights of the pairs and bearings, and the bearings' variances
    struct THeld {
        std::vector<double> pair_w, bearing_w, bearing_C;
    };
    const auto held = [&](const TUnknowns& x) {
        THeld h;
        for (const auto& p : pairs)
            h.pair_w.push_back(weight(linearize(p, x).whitened().first.norm()));
        for (const auto& b : bearings) {
            const TLinearized<1> l = linearize(b, x);
            h.bearing_C.push_back(l.C(0, 0));
            h.bearing_w.push_back(weight(std::abs(l.r[0]) / std::sqrt(l.C(0, 0))));
        }
        return h;
    };
    // F = rᵀ C⁻¹ r over the groups of pairs and the bearings plus the prior's, with `h`'s
    // weights and bearing variances; H its Gauss-Newton Hessian and g its gradient, both / 2
    struct TNormalEquations {
        double F;
        Matrix4 H;
        TUnknowns g;
    };
    const auto normalEquations = [&](const TUnknowns& x, const THeld& h) {
        const TUnknowns d = x - priorMean;
        TNormalEquations n{d.dot(priorInfo.cwiseProduct(d)), priorInfo.asDiagonal(),
                           priorInfo.cwiseProduct(d)};
        // A group's residuals r_p = (readings' part, covariance A_p) − B_p η share one
        // odometry error η ~ N(0, Q): its information is Σ J_pᵀ W_p J_p less
        // Gᵀ Q (I + K Q)⁻¹ G (Woodbury), W_p = w_p A_p⁻¹, K = Σ B_pᵀ W_p B_p,
        // G = Σ B_pᵀ W_p J_p. A pair alone (w = 1): (A + B Q Bᵀ)⁻¹. Its gradient is
        // Σ J_pᵀ s_p with s = C⁻¹ r: s_p = W_p (r_p − B_p η̂), η̂ = N Σ B_pᵀ W_p r_p.
        for (const auto& group : groups) {
            Eigen::Matrix3d K = Eigen::Matrix3d::Zero();
            Matrix34 G = Matrix34::Zero();
            Eigen::Vector3d Gr = Eigen::Vector3d::Zero();
            std::vector<std::pair<TPairLinearized, Eigen::Matrix2d>> members;
            for (const size_t i : group) {
                const TPairLinearized l = linearize(pairs[i], x);
                const Eigen::Matrix2d W = h.pair_w[i] * l.A.inverse();
                n.F += l.r.dot(W * l.r);
                n.H += l.J.transpose() * W * l.J;
                K += l.B.transpose() * W * l.B;
                G += l.B.transpose() * W * l.J;
                Gr += l.B.transpose() * W * l.r;
                members.emplace_back(l, W);
            }
            const Eigen::Matrix3d& Q = pairs[group.front()].Q;
            const Eigen::Matrix3d N =
                Q * (Eigen::Matrix3d::Identity() + K * Q).partialPivLu().inverse();
            const Eigen::Vector3d eta = N * Gr;
            n.F -= Gr.dot(eta);
            n.H -= G.transpose() * N * G;
            // The gradient is that of rᵀ C(x)⁻¹ r with C's own dependence on x,
            // sᵀ ∂r/∂x − ½ sᵀ (∂C/∂x) s (errors in variables): the noise of the readings
            // and of the odometry is in the Jacobian as well as in r (I − Ru holds the
            // odometry's turn), and without the second term an odometry turn as noisy as
            // the turns between readings pulls t towards the points read and k off by
            // tens of per cent. ∂C/∂x = ∂A/∂x + ∂(B Q Bᵀ)/∂x, ∂A/∂θ = S A − A S,
            // ∂A/∂k = 2 A / k; ∂r/∂θ = S (v + r), ∂r/∂k = dr_dk.
            Eigen::Vector3d Bs = Eigen::Vector3d::Zero();
            TUnknowns dBs = TUnknowns::Zero();
            for (const auto& [l, W] : members) {
                const Eigen::Vector2d sp = W * (l.r - l.B * eta), As = W.inverse() * sp;
                n.g.head<3>() += l.J.leftCols<3>().transpose() * sp;
                n.g[2] += (S * l.r).dot(sp) + (S * sp).dot(As);
                n.g[3] += l.dr_dk.dot(sp) - sp.dot(As) / x[3];
                Bs += l.B.transpose() * sp;
                dBs += l.dB.transpose() * sp;
            }
            n.g -= dBs * (Q * Bs)[2];
        }
        for (size_t j = 0; j < bearings.size(); j++) {
            const TLinearized<1> l = linearize(bearings[j], x);
            const double info = h.bearing_w[j] / h.bearing_C[j];
            n.F += info * l.r[0] * l.r[0];
            n.H += info * l.J.transpose() * l.J;
            n.g += info * l.J.transpose() * l.r[0];
        }
        if (holdScale) {  // k = 1: its row and column out
            n.H.row(3).setZero();
            n.H.col(3).setZero();
            n.H(3, 3) = 1;
            n.g[3] = 0;
        }
        return n;
    };
    // On a path of one curvature (a circle) readings shrunk to the sensor (k → 0) at the
    // centre of the turns explain every pair, which then says only that the odometry turns
    // about that point: where the path does not tell k from δ at the stated pose, k is held.
    const TUnknowns stated(0, 0, 0, 1);
    const Matrix4 statedH = normalEquations(stated, held(stated)).H;
    const double scaleConfounding = statedH.inverse()(3, 3) * statedH(3, 3);
    holdScale = holdScale || scaleConfounding >= kToldScaleConfounding;
    // from four turns: a sensor mounted a quarter or half turn off is found too
    std::optional<TSensorPoseCorrection> best;
    double bestCost = 0;
    for (const double start : {0.0, M_PI / 2, M_PI, -M_PI / 2}) {
        TUnknowns x(0, 0, start, 1);
        Matrix4 H;
        for (int iteration = 0; iteration < 20; iteration++) {
            const THeld h = held(x);
            const TNormalEquations n = normalEquations(x, h);
            H = n.H;
            const TUnknowns step = -H.ldlt().solve(n.g);
            // the step halved until F falls (Armijo): where the path has one curvature H is
            // nearly singular, and the full step would leave for where F is not quadratic
            double a = 1;
            while (a > 1e-4 &&
                   !(normalEquations(x + a * step, h).F <= n.F + 2e-4 * a * n.g.dot(step)))
                a /= 2;
            x += a * step;
            if (a * step.cwiseAbs().maxCoeff() < 1e-9) break;
        }
        TSensorPoseCorrection c;
        c.pairs = pairs.size() + bearings.size();
        c.delta = Eigen::Vector3d(x[0], x[1], mrpt::math::wrapToPi(x[2]));
        c.scale = x[3];
        const Matrix4 cov = H.inverse();
        c.cov = cov.topLeftCorner<3, 3>();
        c.scale_std = holdScale ? std::numeric_limits<double>::infinity() : std::sqrt(cov(3, 3));
        c.scale_confounding = scaleConfounding;
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
