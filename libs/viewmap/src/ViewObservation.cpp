#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/viewmap/ViewObservation.h>

#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::viewmap {
namespace {

/// Squared distance q between the two positions; throws when φ is undefined (q = 0).
double squaredBaseline(const mrpt::math::TPose2D& robot, const mrpt::math::TPose2D& view)
{
    const double dx = view.x - robot.x, dy = view.y - robot.y;
    const double q = dx * dx + dy * dy;
    if (!(q > 0)) {
        throw std::domain_error(
            "view observation: the robot stands on the view (zero baseline, bearing undefined)");
    }
    return q;
}

}  // namespace

TViewObservation predictViewObservation(const mrpt::math::TPose2D& robot,
                                        const mrpt::math::TPose2D& view)
{
    squaredBaseline(robot, view);
    // h(x_v, x_l).
    TViewObservation z;
    z.phi = mrpt::math::wrapToPi(std::atan2(view.y - robot.y, view.x - robot.x) - robot.phi);
    z.beta = mrpt::math::wrapToPi(view.phi - robot.phi);
    return z;
}

TViewObservationJacobians viewObservationJacobians(const mrpt::math::TPose2D& robot,
                                                   const mrpt::math::TPose2D& view)
{
    const double q = squaredBaseline(robot, view);
    const double dx = view.x - robot.x, dy = view.y - robot.y;
    // H_v and H_l.
    TViewObservationJacobians J;
    J.H_v << dy / q, -dx / q, -1, 0, 0, -1;
    J.H_l << -dy / q, dx / q, 0, 0, 0, 1;
    return J;
}

}  // namespace mrpt_vslam::viewmap
