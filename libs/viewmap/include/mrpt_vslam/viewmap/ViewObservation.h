#pragma once

#include <mrpt/math/TPose2D.h>

#include <Eigen/Core>

namespace mrpt_vslam::viewmap {

/** Observation of a stored view from the robot (doc/core-features.md §4): the bearing
 *  φ of the view's position in the robot frame (the direction of the translation, the part of
 *  it an essential matrix fixes) and the relative orientation β = θ_l − θ_v [rad]. */
struct TViewObservation {
    double phi = 0;   ///< [rad] atan2(Δy, Δx) − θ_v
    double beta = 0;  ///< [rad] θ_l − θ_v
};

/// Jacobians of h with respect to the robot pose and the view pose (x, y, θ).
struct TViewObservationJacobians {
    Eigen::Matrix<double, 2, 3> H_v;  ///< ∂h/∂x_v
    Eigen::Matrix<double, 2, 3> H_l;  ///< ∂h/∂x_l
};

/** h(x_v, x_l): with Δ = (x_l − x_v, y_l − y_v),
 *  φ = atan2(Δy, Δx) − θ_v and β = θ_l − θ_v, both wrapped by mrpt::math::wrapToPi.
 *  \throw std::domain_error when both positions coincide (φ is undefined). */
TViewObservation predictViewObservation(const mrpt::math::TPose2D& robot,
                                        const mrpt::math::TPose2D& view);

/** H_v, H_l of h, with q = Δx² + Δy²:
 *  H_v = [Δy/q, −Δx/q, −1; 0, 0, −1],  H_l = [−Δy/q, Δx/q, 0; 0, 0, 1].
 *  \throw std::domain_error when both positions coincide. */
TViewObservationJacobians viewObservationJacobians(const mrpt::math::TPose2D& robot,
                                                   const mrpt::math::TPose2D& view);

}  // namespace mrpt_vslam::viewmap
