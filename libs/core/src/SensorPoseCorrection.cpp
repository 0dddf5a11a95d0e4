#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt_vslam/core/SensorPoseCorrection.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <cmath>
#include <optional>

namespace mrpt_vslam::core {

namespace {

Eigen::Matrix2d rotation(double a)
{
    Eigen::Matrix2d R;
    R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    return R;
}

/// r(x), its Jacobian ∂r/∂x and its covariance, of one pair.
struct TLinearized {
    Eigen::Vector2d r;
    Eigen::Matrix<double, 2, 3> J;
    Eigen::Matrix2d C;
};

TLinearized linearize(const TReadingPair& p, const Eigen::Vector3d& x)
{
    Eigen::Matrix2d S;
    S << 0, -1, 1, 0;  // d R(a)/da = R(a) S = S R(a)
    const Eigen::Vector2d t = x.head<2>(), tu(p.u.x, p.u.y);
    const Eigen::Matrix2d Rd = rotation(x[2]), Ru = rotation(p.u.phi);
    const Eigen::Vector2d pj = Rd * p.z_j + t;  // the point in x_j's frame
    TLinearized l;
    l.r = Rd * p.z_i + t - (Ru * pj + tu);
    l.J.leftCols<2>() = Eigen::Matrix2d::Identity() - Ru;
    // ∂r/∂θ = S (R(θ) z_i − Ru R(θ) z_j) is S (tu − (I − Ru) t) plus S r: the readings' noise,
    // which would count as information on θ; the expected Jacobian leaves it out
    l.J.col(2) = S * (tu - l.J.leftCols<2>() * t);
    // ∂(u ⊕ pj)/∂u = [I, S Ru pj]
    Eigen::Matrix<double, 2, 3> Ju;
    Ju.leftCols<2>().setIdentity();
    Ju.col(2) = S * Ru * pj;
    l.C = Rd * p.R_i * Rd.transpose() + Ru * Rd * p.R_j * Rd.transpose() * Ru.transpose() +
          Ju * p.Q * Ju.transpose();
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
    const TLinearized l = linearize(p, delta);
    return l.C.llt().matrixL().solve(l.r);
}

double TSensorPoseCorrection::turnConfounding() const { return cov(2, 2) * cov.inverse()(2, 2); }

double TSensorPoseCorrection::largestMoveStd() const
{
    const double a = cov(0, 0), b = cov(0, 1), c = cov(1, 1);
    return std::sqrt((a + c) / 2 + std::hypot((a - c) / 2, b));
}

TSensorPoseCorrection TSensorPoseCorrection::estimate(const std::vector<TReadingPair>& pairs,
                                                      double huber)
{
    const Eigen::Vector3d priorInfo(1.0, 1.0, 1.0 / (M_PI * M_PI));
    // Σ ρ(‖e‖²) plus the prior's, at `c`
    const auto cost = [&](const TSensorPoseCorrection& c) {
        double sum = c.delta.dot(priorInfo.cwiseProduct(c.delta));
        for (const auto& p : pairs) {
            const double n = c.whitenedResidual(p).norm();
            sum += huber > 0 && n > huber ? 2 * huber * n - huber * huber : n * n;
        }
        return sum;
    };
    // from four turns: a sensor mounted a quarter or half turn off is found too
    std::optional<TSensorPoseCorrection> best;
    double bestCost = 0;
    for (const double start : {0.0, M_PI / 2, M_PI, -M_PI / 2}) {
        TSensorPoseCorrection c;
        c.pairs = pairs.size();
        c.delta[2] = start;
        Eigen::Matrix3d H;
        for (int iteration = 0; iteration < 20; iteration++) {
            H = priorInfo.asDiagonal();
            Eigen::Vector3d g = priorInfo.cwiseProduct(c.delta);
            for (const auto& p : pairs) {
                const TLinearized l = linearize(p, c.delta);
                const Eigen::Matrix2d L = l.C.llt().matrixL();
                const Eigen::Vector2d e = L.triangularView<Eigen::Lower>().solve(l.r);
                const Eigen::Matrix<double, 2, 3> Je = L.triangularView<Eigen::Lower>().solve(l.J);
                const double norm = e.norm();
                const double w = huber > 0 && norm > huber ? huber / norm : 1.0;  // IRLS
                H += w * Je.transpose() * Je;
                g += w * Je.transpose() * e;
            }
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
    for (const auto& p : pairs)
        if (huber > 0 && best->whitenedResidual(p).norm() > huber) best->outlier_pairs++;
    return *best;
}

}  // namespace mrpt_vslam::core
