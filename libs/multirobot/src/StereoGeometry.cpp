#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt_vslam/multirobot/StereoGeometry.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mrpt_vslam::multirobot {

namespace {

bool nearlyEqual(double a, double b)
{
    return std::abs(a - b) <= 1e-6 * std::max(1.0, std::max(std::abs(a), std::abs(b)));
}

/// Throws unless `cam` can be read: finite distortion of the plumb_bob model.
void checkReadable(const mrpt::img::TCamera& cam, const std::string& which)
{
    if (cam.distortion == mrpt::img::DistortionModel::kannala_brandt)
        throw std::invalid_argument("the " + which +
                                    " camera has the kannala_brandt (fisheye) model, which is "
                                    "not read: only the plumb_bob model");
    for (const double k : cam.dist)
        if (!std::isfinite(k))
            throw std::invalid_argument("the " + which + " camera has a non-finite distortion");
}

bool distorted(const mrpt::img::TCamera& cam)
{
    return std::any_of(cam.dist.begin(), cam.dist.end(), [](double k) { return k != 0; });
}

}  // namespace

StereoGeometry::StereoGeometry(double fx, double fy, double cx, double cy, double baseline,
                               double disparity_offset)
    : m_fx(fx),
      m_fy(fy),
      m_cx(cx),
      m_cy(cy),
      m_baseline(baseline),
      m_disparity_offset(disparity_offset)
{
    for (const double v : {fx, fy, cx, cy, baseline, disparity_offset})
        if (!std::isfinite(v))
            throw std::invalid_argument("stereo camera parameters must be finite");
    if (!(fx > 0 && fy > 0))
        throw std::invalid_argument("stereo camera focal lengths must be positive");
    if (!(baseline > 0))
        throw std::invalid_argument("stereo baseline must be positive (right camera at +x)");
}

std::string StereoGeometry::whyNotRectified(const mrpt::obs::CObservationStereoImages& obs)
{
    // what cannot be read at all
    const auto& left = obs.leftCamera;
    const auto& right = obs.rightCamera;
    checkReadable(left, "left");
    checkReadable(right, "right");
    const double lk[4] = {left.fx(), left.fy(), left.cx(), left.cy()};
    const double rk[4] = {right.fx(), right.fy(), right.cx(), right.cy()};
    for (int i = 0; i < 4; i++)
        if (!std::isfinite(lk[i]) || !std::isfinite(rk[i]))
            throw std::invalid_argument("the camera intrinsics are not finite");
    if (!(lk[0] > 0 && lk[1] > 0 && rk[0] > 0 && rk[1] > 0))
        throw std::invalid_argument("the camera focal lengths must be positive");
    const auto& pose = obs.rightCameraPose;
    const auto& q = pose.quat();
    for (const double v : {pose.x(), pose.y(), pose.z(), q.r(), q.x(), q.y(), q.z()})
        if (!std::isfinite(v)) throw std::invalid_argument("the right camera pose is not finite");
    if (!(pose.x() > 0))
        throw std::invalid_argument("the right camera must be at +x of the left one (baseline " +
                                    std::to_string(pose.x()) + " m)");

    // what a rectification changes
    if (distorted(left)) return "the left camera has non-zero distortion parameters";
    if (distorted(right)) return "the right camera has non-zero distortion parameters";
    for (const int i : {0, 1, 3})  // c_x may differ: the disparity's offset
        if (!nearlyEqual(lk[i], rk[i])) return "left and right intrinsics differ (fx fy cy)";
    const double angle =
        2 * std::atan2(std::sqrt(q.x() * q.x() + q.y() * q.y() + q.z() * q.z()), std::abs(q.r()));
    if (angle > 1e-6) {
        std::ostringstream msg;
        msg << "the right camera is rotated by " << angle * 180 / M_PI
            << " deg w.r.t. the left one";
        return msg.str();
    }
    if (std::abs(pose.y()) > 1e-6 * pose.x() || std::abs(pose.z()) > 1e-6 * pose.x())
        return "the right camera is off the left camera's x axis";
    return {};
}

StereoGeometry StereoGeometry::fromObservation(const mrpt::obs::CObservationStereoImages& obs)
{
    if (const std::string why = whyNotRectified(obs); !why.empty())
        throw std::invalid_argument("images are not rectified: " + why);
    const auto& left = obs.leftCamera;
    return StereoGeometry(left.fx(), left.fy(), left.cx(), left.cy(), obs.rightCameraPose.x(),
                          left.cx() - obs.rightCamera.cx());
}

mrpt::math::TPoint3D StereoGeometry::triangulate(const TStereoPixel& px) const
{
    if (!(std::isfinite(px.disparity) && px.disparity > 0) || !std::isfinite(px.row) ||
        !std::isfinite(px.col))
        throw std::invalid_argument("triangulate: need finite pixel and disparity > 0");
    // Eq. 12, y down (Y = −Y_Eq.12)
    const double k = m_baseline / px.disparity;
    return {k * (px.col - m_cx), k * (m_fx / m_fy) * (px.row - m_cy), k * m_fx};
}

mrpt::math::CMatrixDouble33 StereoGeometry::jacobian(const TStereoPixel& px) const
{
    const mrpt::math::TPoint3D p = triangulate(px);
    const double d = px.disparity;
    // J = ∂(X, Y, Z)/∂(d, r, c) of Eq. 12
    mrpt::math::CMatrixDouble33 J;
    J.setZero();
    J(0, 0) = -p.x / d;
    J(1, 0) = -p.y / d;
    J(2, 0) = -p.z / d;
    J(1, 1) = m_baseline * (m_fx / m_fy) / d;
    J(0, 2) = m_baseline / d;
    return J;
}

mrpt::math::CMatrixDouble33 StereoGeometry::covariance(const TStereoPixel& px,
                                                       const TStereoPixelNoise& noise) const
{
    const mrpt::math::CMatrixDouble33 J_mrpt = jacobian(px);
    const auto J = J_mrpt.asEigen();
    const Eigen::Vector3d var(noise.sigma_disparity * noise.sigma_disparity,
                              noise.sigma_row * noise.sigma_row, noise.sigma_col * noise.sigma_col);
    // R_t = J R_sp Jᵀ, R_sp = diag(σ_d², σ_r², σ_c²)   (Sec. 3.2)
    const Eigen::Matrix3d R = J * var.asDiagonal() * J.transpose();
    return mrpt::math::CMatrixDouble33(0.5 * (R + R.transpose()));
}

TStereoPixel StereoGeometry::project(const mrpt::math::TPoint3D& point) const
{
    if (!(std::isfinite(point.x) && std::isfinite(point.y) && std::isfinite(point.z) &&
          point.z > 0))
        throw std::invalid_argument("project: need a finite point with z > 0");
    TStereoPixel px;
    px.col = m_cx + m_fx * point.x / point.z;
    px.row = m_cy + m_fy * point.y / point.z;
    px.disparity = m_fx * m_baseline / point.z;
    return px;
}

}  // namespace mrpt_vslam::multirobot
