#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/viewmap/ViewMapEKF.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "ArgumentChecks.h"

namespace mrpt_vslam::viewmap {

using detail::requireCovariance;
using detail::requireFinite;
using mrpt::math::TPose2D;
using mrpt::math::wrapToPi;

ViewMapEKF::ViewMapEKF(const TPose2D& start, const Eigen::Matrix3d& P0)
    : m_x(Eigen::Vector3d(start.x, start.y, wrapToPi(start.phi))), m_P(0.5 * (P0 + P0.transpose()))
{
    requireFinite(start, "ViewMapEKF: start pose");
    requireCovariance(P0, false, "ViewMapEKF: P0");
}

void ViewMapEKF::setCameraPosition(const mrpt::math::TPoint2D& camera_in_robot)
{
    if (!std::isfinite(camera_in_robot.x) || !std::isfinite(camera_in_robot.y))
        throw std::invalid_argument("ViewMapEKF: camera position on the robot is not finite");
    m_camera = camera_in_robot;
}

size_t ViewMapEKF::viewCount() const { return size_t(m_x.size() - 3) / 3; }

TPose2D ViewMapEKF::robotPose() const { return {m_x(0), m_x(1), m_x(2)}; }

TPose2D ViewMapEKF::viewPose(size_t i) const
{
    const Eigen::Index l = viewOffset(i);
    return {m_x(l), m_x(l + 1), m_x(l + 2)};
}

Eigen::Matrix3d ViewMapEKF::robotCovariance() const { return m_P.topLeftCorner<3, 3>(); }

Eigen::Matrix3d ViewMapEKF::viewCovariance(size_t i) const
{
    const Eigen::Index l = viewOffset(i);
    return m_P.block<3, 3>(l, l);
}

void ViewMapEKF::predict(const TPose2D& increment, const Eigen::Matrix3d& Q)
{
    requireFinite(increment, "ViewMapEKF::predict: increment");
    requireCovariance(Q, false, "ViewMapEKF::predict: Q");
    // f(x_v, u) and its Jacobians F_x, F_u at the prior heading.
    const double c = std::cos(m_x(2)), s = std::sin(m_x(2));
    const double dx = increment.x, dy = increment.y;
    Eigen::Matrix3d F_x, F_u;
    F_x << 1, 0, -dx * s - dy * c, 0, 1, dx * c - dy * s, 0, 0, 1;
    F_u << c, -s, 0, s, c, 0, 0, 0, 1;
    m_x(0) += dx * c - dy * s;
    m_x(1) += dx * s + dy * c;
    m_x(2) = wrapToPi(m_x(2) + increment.phi);
    // Block-wise in O(N): P_vv, then P_vl ← F_x P_vl and its transpose; P_ll unchanged.
    const Eigen::Matrix3d P_vv =
        F_x * m_P.topLeftCorner<3, 3>() * F_x.transpose() + F_u * Q * F_u.transpose();
    m_P.topLeftCorner<3, 3>() = 0.5 * (P_vv + P_vv.transpose());
    const Eigen::Index m = m_P.cols() - 3;
    m_P.topRightCorner(3, m) = F_x * m_P.topRightCorner(3, m);
    m_P.bottomLeftCorner(m, 3) = m_P.topRightCorner(3, m).transpose();
}

size_t ViewMapEKF::addView()
{
    const Eigen::Index n = m_x.size();
    m_x.conservativeResize(n + 3);
    m_x.tail<3>() = m_x.head<3>();
    // x_new = x_v (G = I₃), so the new row and column are copies of the robot's.
    m_P.conservativeResize(n + 3, n + 3);
    m_P.bottomLeftCorner(3, n) = m_P.topLeftCorner(3, n);
    m_P.topRightCorner(n, 3) = m_P.topLeftCorner(n, 3);
    m_P.bottomRightCorner<3, 3>() = m_P.topLeftCorner<3, 3>();
    return viewCount() - 1;
}

ViewMapEKF::TUpdateResult ViewMapEKF::update(size_t view, const TViewObservation& z,
                                             const Eigen::Matrix2d& R, double gate)
{
    if (!(std::isfinite(z.phi) && std::isfinite(z.beta))) {
        throw std::invalid_argument("ViewMapEKF::update: observation is not finite");
    }
    requireCovariance(R, true, "ViewMapEKF::update: R");
    if (!(gate > 0)) throw std::invalid_argument("ViewMapEKF::update: gate must be > 0");

    const TObservationTerms o = observationTerms(view);
    const Eigen::MatrixX2d& PHt = o.PHt;
    TUpdateResult result;
    result.innovation << wrapToPi(z.phi - o.h.phi), wrapToPi(z.beta - o.h.beta);
    const Eigen::Matrix2d S = o.HPHt + R;
    const Eigen::Matrix2d S_inv = S.inverse();
    result.nis = result.innovation.dot(S_inv * result.innovation);
    if (result.nis > gate) return result;

    const Eigen::MatrixX2d K = PHt * S_inv;
    m_x += K * result.innovation;
    for (Eigen::Index i = 2; i < m_x.size(); i += 3) m_x(i) = wrapToPi(m_x(i));
    // Joseph form (I − KH) P (I − KH)ᵀ + K R Kᵀ. With H P = (P Hᵀ)ᵀ (P symmetric) it expands
    // exactly, for any gain K, to P − K(HP) − (K(HP))ᵀ + K (HPHᵀ + R) Kᵀ, which costs O(n²)
    // instead of the dense products' O(n³).
    const Eigen::MatrixXd KHP = K * PHt.transpose();
    m_P += K * S * K.transpose() - KHP - KHP.transpose();
    m_P = (0.5 * (m_P + m_P.transpose())).eval();
    result.accepted = true;
    return result;
}

ViewMapEKF::TObservationTerms ViewMapEKF::observationTerms(size_t view) const
{
    // H = [H_v 0 … H_l … 0] has six non-zero columns, so P Hᵀ (n × 2) needs only the
    // robot's and the view's columns of P, and H P Hᵀ only their rows of P Hᵀ.
    const Eigen::Index l = viewOffset(view);
    const TPose2D robot = robotPose(), landmark = viewPose(view);
    TObservationTerms o{predictViewObservation(robot, landmark, m_camera),
                        viewObservationJacobians(robot, landmark, m_camera),
                        {},
                        {}};
    o.PHt = m_P.leftCols<3>() * o.J.H_v.transpose() + m_P.middleCols<3>(l) * o.J.H_l.transpose();
    o.HPHt = o.J.H_v * o.PHt.topRows<3>() + o.J.H_l * o.PHt.middleRows<3>(l);
    return o;
}

ViewMapEKF::TPredictedObservation ViewMapEKF::predictObservation(size_t view) const
{
    const TObservationTerms o = observationTerms(view);
    return {o.h, 0.5 * (o.HPHt + o.HPHt.transpose())};
}

Eigen::Matrix3d ViewMapEKF::robotCovarianceAfterUpdates(
    const std::vector<THypotheticalObservation>& observations,
    const Eigen::Matrix3d& added_P_vv) const
{
    // The sub-state [x_v, x_l1, ..., x_lm] of the observed views: H is zero elsewhere.
    const auto m = static_cast<Eigen::Index>(observations.size());
    std::vector<Eigen::Index> offset{0};
    for (const auto& o : observations) {
        requireCovariance(o.R, true, "ViewMapEKF::robotCovarianceAfterUpdates: R");
        const Eigen::Index l = viewOffset(o.view);
        if (std::find(offset.begin(), offset.end(), l) != offset.end())
            throw std::invalid_argument("ViewMapEKF::robotCovarianceAfterUpdates: view " +
                                        std::to_string(o.view) + " listed twice");
        offset.push_back(l);
    }
    Eigen::MatrixXd P(3 + 3 * m, 3 + 3 * m);
    for (Eigen::Index a = 0; a <= m; a++)
        for (Eigen::Index b = 0; b <= m; b++)
            P.block<3, 3>(3 * a, 3 * b) = m_P.block<3, 3>(offset[size_t(a)], offset[size_t(b)]);
    P.topLeftCorner<3, 3>() += added_P_vv;
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * m, 3 + 3 * m);
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(2 * m, 2 * m);
    for (Eigen::Index k = 0; k < m; k++) {
        const auto& o = observations[size_t(k)];
        const auto J = viewObservationJacobians(robotPose(), viewPose(o.view), m_camera);
        H.block<2, 3>(2 * k, 0) = J.H_v;
        H.block<2, 3>(2 * k, 3 + 3 * k) = J.H_l;
        S.block<2, 2>(2 * k, 2 * k) = o.R;
    }
    const Eigen::MatrixXd PHt_v = P.topRows<3>() * H.transpose();
    S += H * P * H.transpose();
    const Eigen::Matrix3d P_vv = P.topLeftCorner<3, 3>() - PHt_v * S.llt().solve(PHt_v.transpose());
    return 0.5 * (P_vv + P_vv.transpose());
}

double ViewMapEKF::robotNEES(const TPose2D& truth) const
{
    requireFinite(truth, "ViewMapEKF::robotNEES: true pose");
    const Eigen::Vector3d e(m_x(0) - truth.x, m_x(1) - truth.y, wrapToPi(m_x(2) - truth.phi));
    const Eigen::LLT<Eigen::Matrix3d> llt(robotCovariance());
    if (llt.info() != Eigen::Success) {
        throw std::domain_error("ViewMapEKF::robotNEES: P_vv is not positive definite");
    }
    return e.dot(llt.solve(e));
}

Eigen::Index ViewMapEKF::viewOffset(size_t i) const
{
    if (i >= viewCount()) {
        throw std::invalid_argument("ViewMapEKF: view index " + std::to_string(i) +
                                    " out of range (" + std::to_string(viewCount()) + " views)");
    }
    return Eigen::Index(3 + 3 * i);
}

}  // namespace mrpt_vslam::viewmap
