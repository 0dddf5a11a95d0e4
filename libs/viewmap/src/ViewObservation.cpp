#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/viewmap/ViewObservation.h>

#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::viewmap {
namespace {

/// The camera centre of a pose: (x, y) + R(θ) t.
Eigen::Vector2d cameraCentre(const mrpt::math::TPose2D& pose, const mrpt::math::TPoint2D& t)
{
    const double c = std::cos(pose.phi), s = std::sin(pose.phi);
    return {pose.x + c * t.x - s * t.y, pose.y + s * t.x + c * t.y};
}

/// Δ = c_l − c_v and q = |Δ|²; throws when φ is undefined (q = 0).
Eigen::Vector2d baseline(const mrpt::math::TPose2D& robot, const mrpt::math::TPose2D& view,
                         const mrpt::math::TPoint2D& camera, double& q)
{
    const Eigen::Vector2d d = cameraCentre(view, camera) - cameraCentre(robot, camera);
    q = d.squaredNorm();
    if (!(q > 0)) {
        throw std::domain_error(
            "view observation: the robot stands on the view (zero baseline, bearing undefined)");
    }
    return d;
}

}  // namespace

TViewObservation predictViewObservation(const mrpt::math::TPose2D& robot,
                                        const mrpt::math::TPose2D& view,
                                        const mrpt::math::TPoint2D& camera)
{
    double q;
    const Eigen::Vector2d d = baseline(robot, view, camera, q);
    // h(x_v, x_l).
    TViewObservation z;
    z.phi = mrpt::math::wrapToPi(std::atan2(d.y(), d.x()) - robot.phi);
    z.beta = mrpt::math::wrapToPi(view.phi - robot.phi);
    return z;
}

TViewObservationJacobians viewObservationJacobians(const mrpt::math::TPose2D& robot,
                                                   const mrpt::math::TPose2D& view,
                                                   const mrpt::math::TPoint2D& camera)
{
    double q;
    const Eigen::Vector2d d = baseline(robot, view, camera, q);
    const double dx = d.x(), dy = d.y();
    // ∂(R(θ) t)/∂θ of each pose: how the camera centre moves as the pose turns
    const mrpt::math::TPoint2D turned(-camera.y, camera.x);
    const Eigen::Vector2d dv = cameraCentre({0, 0, robot.phi}, turned);
    const Eigen::Vector2d dl = cameraCentre({0, 0, view.phi}, turned);
    // H_v and H_l.
    TViewObservationJacobians J;
    J.H_v << dy / q, -dx / q, (dy * dv.x() - dx * dv.y()) / q - 1, 0, 0, -1;
    J.H_l << -dy / q, dx / q, (dx * dl.y() - dy * dl.x()) / q, 0, 0, 1;
    return J;
}

}  // namespace mrpt_vslam::viewmap
