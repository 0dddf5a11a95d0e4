#pragma once

#include <mrpt/math/TPose2D.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <string>

/** Checks of the arguments the view map and its EKF are given: each throws
 *  std::invalid_argument naming `what`. */
namespace mrpt_vslam::viewmap::detail {

/// Relative rounding allowed in the symmetry and the eigenvalues of a covariance argument.
inline constexpr double kCovarianceTolerance = 1e-12;

inline void requireFinite(const mrpt::math::TPose2D& p, const std::string& what)
{
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.phi)))
        throw std::invalid_argument(what + " is not finite");
}

/// Throws unless M is finite, symmetric and positive semidefinite (definite with `definite`).
template <int N>
void requireCovariance(const Eigen::Matrix<double, N, N>& M, bool definite, const std::string& what)
{
    const double scale = M.cwiseAbs().maxCoeff();
    if (!M.allFinite() || (M - M.transpose()).cwiseAbs().maxCoeff() > kCovarianceTolerance * scale)
        throw std::invalid_argument(what + " is not finite and symmetric");
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(M, Eigen::EigenvaluesOnly);
    const double lambda_min = eig.eigenvalues()(0);
    if (definite && !(lambda_min > kCovarianceTolerance * scale))
        throw std::invalid_argument(what + " is not positive definite");
    if (!definite && lambda_min < -kCovarianceTolerance * scale)
        throw std::invalid_argument(what + " is not positive semidefinite");
}

}  // namespace mrpt_vslam::viewmap::detail
