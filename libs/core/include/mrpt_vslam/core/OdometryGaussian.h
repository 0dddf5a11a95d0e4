#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/random/RandomGenerators.h>

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

namespace mrpt::obs {
class CActionRobotMovement2D;
}

namespace mrpt_vslam::core {

/** A floor added to the odometry covariance (as standard deviations) so that a particle
 *  filter's proposal never degenerates, even where the odometry claims to be exact. */
struct TMotionNoiseFloor {
    double std_xy = 0.002;              ///< [m] (ini: min_motion_std_xy)
    double std_phi = 0.1 * M_PI / 180;  ///< [rad] (ini: min_motion_std_phi_deg)

    /// Reads min_motion_std_xy and min_motion_std_phi_deg (absent: unchanged); both > 0.
    /// \throw std::invalid_argument naming the section and key
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
    void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};

/** One odometry increment as a Gaussian in the robot frame of the previous pose, with the
 *  noise floor added, and the Cholesky factor L of its covariance (cov = L Lᵀ). */
struct TOdometryGaussian {
    mrpt::math::TPose2D mean;
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero(), L = Eigen::Matrix3d::Zero();

    /** From an odometry action (nullptr: no motion, the floor only).
     *  \throw std::runtime_error on a non-finite increment or covariance, or one that is not
     *  positive definite */
    static TOdometryGaussian from(const mrpt::obs::CActionRobotMovement2D* odometry,
                                  const TMotionNoiseFloor& floor);
};

/// The covariance in the map frame of an odometry increment's covariance `cov`, given in the
/// frame of the pose it starts from (heading `phi`): J cov Jᵀ, J = ∂(a ⊕ b)/∂b the rotation
/// of the increment into the map frame.
inline Eigen::Matrix3d incrementCovInMapFrame(const Eigen::Matrix3d& cov, double phi)
{
    const double c = std::cos(phi), s = std::sin(phi);
    Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
    J.topLeftCorner<2, 2>() << c, -s, s, c;
    return J * cov * J.transpose();
}

/// A sample of N(0, L Lᵀ) from `rng` (three normal draws, in order).
Eigen::Vector3d drawGaussian(mrpt::random::CRandomGenerator& rng, const Eigen::Matrix3d& L);

/** `count` samples of N(0, I₃) from `rng` into `n` (resized to `count`; a filter keeps it from
 *  step to step), the same bit for bit as `count` calls of drawGaussian() in a serial loop, so
 *  L * n[i] is the i-th drawGaussian(rng, L): a filter draws its particles' noise before
 *  updating them in parallel. The generator's sequence is drawn serially, the logarithms and
 *  roots of the normals on up to `threads` threads. Returns `n`. */
const std::vector<Eigen::Vector3d>& drawStandardNormals(mrpt::random::CRandomGenerator& rng,
                                                        size_t count,
                                                        std::vector<Eigen::Vector3d>& n,
                                                        unsigned threads = 1);

}  // namespace mrpt_vslam::core
