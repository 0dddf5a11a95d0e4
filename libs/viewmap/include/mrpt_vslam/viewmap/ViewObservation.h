#pragma once

#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>

#include <Eigen/Core>

namespace mrpt_vslam::viewmap {

/** Observation of a stored view from the robot (doc/core-features.md §4): the bearing
 *  φ of the view's camera position in the robot frame (the direction of the translation between
 *  the two camera centres, the part of it an essential matrix fixes) and the relative
 *  orientation β = θ_l − θ_v [rad]. */
struct TViewObservation {
    double phi = 0;   ///< [rad] atan2(Δy, Δx) − θ_v
    double beta = 0;  ///< [rad] θ_l − θ_v
};

/// Jacobians of h with respect to the robot pose and the view pose (x, y, θ).
struct TViewObservationJacobians {
    Eigen::Matrix<double, 2, 3> H_v;  ///< ∂h/∂x_v
    Eigen::Matrix<double, 2, 3> H_l;  ///< ∂h/∂x_l
};

/** h(x_v, x_l) for a camera at `camera` (t) in the robot frame: with the camera centres
 *  c = (x, y) + R(θ) t and Δ = c_l − c_v, φ = atan2(Δy, Δx) − θ_v and β = θ_l − θ_v, both
 *  wrapped by mrpt::math::wrapToPi (t = 0: the robots' positions, Valiente et al. 2015).
 *  \throw std::domain_error when both camera centres coincide (φ is undefined). */
TViewObservation predictViewObservation(const mrpt::math::TPose2D& robot,
                                        const mrpt::math::TPose2D& view,
                                        const mrpt::math::TPoint2D& camera = {0, 0});

/** H_v, H_l of h, with q = Δx² + Δy² and d = ∂(R(θ) t)/∂θ = R(θ) (−t_y, t_x) of each pose:
 *  H_v = [Δy/q, −Δx/q, (Δy d_vx − Δx d_vy)/q − 1; 0, 0, −1],
 *  H_l = [−Δy/q, Δx/q, (Δx d_ly − Δy d_lx)/q; 0, 0, 1].
 *  \throw std::domain_error when both camera centres coincide. */
TViewObservationJacobians viewObservationJacobians(const mrpt::math::TPose2D& robot,
                                                   const mrpt::math::TPose2D& view,
                                                   const mrpt::math::TPoint2D& camera = {0, 0});

}  // namespace mrpt_vslam::viewmap
