#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/viewmap/ViewObservation.h>

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace mrpt_vslam::viewmap {

/** EKF of view-based SLAM (doc/view-slam.md §3) over the state
 *  x = [x_v, x_l1, …, x_lN] (3 + 3N): the planar robot pose x_v = (x, y, θ) followed by the
 *  poses of the N views, with the full covariance P.
 *
 *   - predict(): odometry composes x_v; only P_vv and the cross blocks P_vl change, in O(N).
 *   - addView(): a new view at the current robot pose. It is a deterministic copy of x_v, so
 *     cloning the robot's row and column of P is the exact augmentation (G = I₃).
 *   - update(): one observation z = (φ, β) of a view with χ² gating on the NIS. The gain
 *     and the Joseph-form covariance use only the six non-zero columns of H, in O(n²).
 *
 *  Every θ of the state stays wrapped by mrpt::math::wrapToPi. P is kept exactly symmetric.
 *
 *  Usage: `ViewMapEKF ekf(start); ekf.predict(u, Q); const size_t l = ekf.addView();
 *  if (ekf.update(l, z, R, 9.21).accepted) ...`
 */
class ViewMapEKF {
  public:
    /// Outcome of update().
    struct TUpdateResult {
        bool accepted = false;  ///< false: gated out, the filter is unchanged
        double nis = 0;         ///< normalised innovation squared νᵀ S⁻¹ ν
        Eigen::Vector2d innovation = Eigen::Vector2d::Zero();  ///< [rad] ν, both angles wrapped
    };

    /** Robot at `start` with covariance P0 and no views.
     *  \throw std::invalid_argument for a non-finite pose or a P0 that is not symmetric PSD. */
    explicit ViewMapEKF(const mrpt::math::TPose2D& start,
                        const Eigen::Matrix3d& P0 = Eigen::Matrix3d::Zero());

    /** The camera's position on the robot, t in the robot frame [m] (default 0): the views are
     *  the robot's poses, the observations are between the camera centres (ViewObservation.h).
     *  \throw std::invalid_argument for a non-finite t. */
    void setCameraPosition(const mrpt::math::TPoint2D& camera_in_robot);
    const mrpt::math::TPoint2D& cameraPosition() const { return m_camera; }

    size_t viewCount() const;
    mrpt::math::TPose2D robotPose() const;
    /// \throw std::invalid_argument if i ≥ viewCount().
    mrpt::math::TPose2D viewPose(size_t i) const;
    const Eigen::VectorXd& mean() const { return m_x; }
    const Eigen::MatrixXd& covariance() const { return m_P; }
    /// P_vv.
    Eigen::Matrix3d robotCovariance() const;
    /// P_lili. \throw std::invalid_argument if i ≥ viewCount().
    Eigen::Matrix3d viewCovariance(size_t i) const;

    /** Prediction with the odometry increment u = (Δx, Δy, Δθ), expressed in the robot
     *  frame at t−1, of covariance Q: x_v ← x_v ⊕ u, P_vv ← F_x P_vv F_xᵀ + F_u Q F_uᵀ,
     *  P_vl ← F_x P_vl; the view blocks P_ll do not change.
     *  \throw std::invalid_argument for a non-finite u or a Q that is not symmetric PSD. */
    void predict(const mrpt::math::TPose2D& increment, const Eigen::Matrix3d& Q);

    /** Augmentation: appends a view at the current robot pose. Its block and its cross
     *  terms are copies of P_vv and of the robot's cross terms (x_l = x_v exactly).
     *  \return the index of the new view. */
    size_t addView();

    /** EKF update with the observation z of view `view` and its covariance R.
     *  The update is rejected, leaving the filter unchanged, when NIS > gate (a χ²₂ threshold,
     *  e.g. 9.21 for 99 %; +∞ accepts everything).
     *  \throw std::invalid_argument for a bad view index, a non-finite z, an R that is not
     *         symmetric positive definite or a gate that is not > 0.
     *  \throw std::domain_error when the estimated robot stands on the view (h undefined). */
    TUpdateResult update(size_t view, const TViewObservation& z, const Eigen::Matrix2d& R,
                         double gate);

    /// Predicted observation of a view and its covariance without the sensor noise.
    struct TPredictedObservation {
        TViewObservation z;                              ///< h(x_v, x_l)
        Eigen::Matrix2d HPHt = Eigen::Matrix2d::Zero();  ///< H P Hᵀ
    };

    /** h and H P Hᵀ of view `view` at the current estimate: the centre and the spread of the
     *  area where its points can appear in the current image (doc/view-slam.md §4.1).
     *  \throw std::invalid_argument for a bad view index.
     *  \throw std::domain_error when the estimated robot stands on the view. */
    TPredictedObservation predictObservation(size_t view) const;

    /// One observation of a view for robotCovarianceAfterUpdates(): the view and its noise.
    struct THypotheticalObservation {
        size_t view = 0;
        Eigen::Matrix2d R = Eigen::Matrix2d::Identity();
    };

    /** P_vv that one EKF update with all `observations` at once (stacked H and R, linearized
     *  at the current mean) would leave, without changing the filter:
     *  P_vv − (P Hᵀ)_v S⁻¹ (P Hᵀ)_vᵀ, from the blocks of the robot and the observed views only.
     *  With `added_P_vv`, P_vv is first taken as P_vv + added_P_vv (a motion still to come).
     *  For the information-based view initialization (doc/view-slam.md §4.2).
     *  \throw as predictObservation() for each view, and std::invalid_argument for an R that
     *  is not symmetric positive definite or a view listed twice. */
    Eigen::Matrix3d robotCovarianceAfterUpdates(
        const std::vector<THypotheticalObservation>& observations,
        const Eigen::Matrix3d& added_P_vv = Eigen::Matrix3d::Zero()) const;

    /** NEES of the robot pose against the true pose: eᵀ P_vv⁻¹ e, e = x_v − truth with the
     *  angle wrapped.
     *  \throw std::invalid_argument for a non-finite truth.
     *  \throw std::domain_error if P_vv is not positive definite. */
    double robotNEES(const mrpt::math::TPose2D& truth) const;

  private:
    /// The terms of an observation of view `view`: h, the two non-zero blocks of H
    /// and P Hᵀ over `rows` (all n rows, or only the robot's and the view's).
    struct TObservationTerms {
        TViewObservation h;
        TViewObservationJacobians J;
        Eigen::MatrixX2d PHt;  ///< P Hᵀ, n × 2
        Eigen::Matrix2d HPHt;  ///< H P Hᵀ
    };
    TObservationTerms observationTerms(size_t view) const;

    /// Offset of view i's pose in the state; throws std::invalid_argument if i is out of range.
    Eigen::Index viewOffset(size_t i) const;

    Eigen::VectorXd m_x;                  ///< [x_v, x_l1, …, x_lN]
    Eigen::MatrixXd m_P;                  ///< covariance of m_x
    mrpt::math::TPoint2D m_camera{0, 0};  ///< the camera's position on the robot
};

}  // namespace mrpt_vslam::viewmap
