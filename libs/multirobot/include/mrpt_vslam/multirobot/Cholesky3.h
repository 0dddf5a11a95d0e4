#pragma once

#include <Eigen/Core>
#include <cmath>

namespace mrpt_vslam::multirobot {

/// Closed-form Cholesky factor Z = L Lᵀ of a symmetric positive-definite 3 × 3 matrix (the
/// generic Eigen path costs more than the whole update at this size).
struct Cholesky3 {
    double l00, l10, l11, l20, l21, l22;
    bool ok;
    explicit Cholesky3(const Eigen::Matrix3d& Z)
    {
        l00 = std::sqrt(Z(0, 0));
        l10 = Z(1, 0) / l00;
        l20 = Z(2, 0) / l00;
        l11 = std::sqrt(Z(1, 1) - l10 * l10);
        l21 = (Z(2, 1) - l20 * l10) / l11;
        l22 = std::sqrt(Z(2, 2) - l20 * l20 - l21 * l21);
        ok = l00 > 0 && l11 > 0 && l22 > 0;  // false for NaN too
    }
    /// L⁻¹ v
    Eigen::Vector3d whiten(const Eigen::Vector3d& v) const
    {
        const double w0 = v[0] / l00, w1 = (v[1] - l10 * w0) / l11;
        return {w0, w1, (v[2] - l20 * w0 - l21 * w1) / l22};
    }
    /// L
    Eigen::Matrix3d factor() const
    {
        Eigen::Matrix3d L;
        L << l00, 0, 0, l10, l11, 0, l20, l21, l22;
        return L;
    }
    double logDet() const { return 2 * (std::log(l00) + std::log(l11) + std::log(l22)); }
    /// log N(v; 0, Z) of a v whose squared Mahalanobis distance vᵀ Z⁻¹ v is D
    double logGaussian(double D) const { return -0.5 * (3 * std::log(2 * M_PI) + logDet() + D); }
    /// Z⁻¹ = L⁻ᵀ L⁻¹
    Eigen::Matrix3d inverse() const
    {
        Eigen::Matrix3d Li = Eigen::Matrix3d::Zero();
        Li(0, 0) = 1 / l00;
        Li(1, 1) = 1 / l11;
        Li(2, 2) = 1 / l22;
        Li(1, 0) = -l10 * Li(0, 0) / l11;
        Li(2, 1) = -l21 * Li(1, 1) / l22;
        Li(2, 0) = -(l20 * Li(0, 0) + l21 * Li(1, 0)) / l22;
        return Li.transpose() * Li;
    }
};

}  // namespace mrpt_vslam::multirobot
