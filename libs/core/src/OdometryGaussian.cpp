#include <mrpt/core/bits_math.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/core/OdometryGaussian.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::core {

void TMotionNoiseFloor::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                           const std::string& section)
{
    std_xy = cfg.read_double(section, "min_motion_std_xy", std_xy);
    std_phi =
        mrpt::DEG2RAD(cfg.read_double(section, "min_motion_std_phi_deg", mrpt::RAD2DEG(std_phi)));
    if (!(std_xy > 0) || !std::isfinite(std_xy))
        throw std::invalid_argument("[" + section + "] min_motion_std_xy: must be > 0");
    if (!(std_phi > 0) || !std::isfinite(std_phi))
        throw std::invalid_argument("[" + section + "] min_motion_std_phi_deg: must be > 0");
}

void TMotionNoiseFloor::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                         const std::string& section) const
{
    cfg.write(section, "min_motion_std_xy", std_xy);
    cfg.write(section, "min_motion_std_phi_deg", mrpt::RAD2DEG(std_phi));
}

TOdometryGaussian TOdometryGaussian::from(const mrpt::obs::CActionRobotMovement2D* odometry,
                                          const TMotionNoiseFloor& floor)
{
    TOdometryGaussian g;
    if (odometry) {
        mrpt::math::CMatrixDouble33 cov;
        mrpt::poses::CPose2D mean;
        odometry->poseChange->getCovarianceAndMean(cov, mean);
        g.mean = mean.asTPose();
        g.cov = cov.asEigen();
    }
    g.cov.diagonal() += Eigen::Vector3d(floor.std_xy * floor.std_xy, floor.std_xy * floor.std_xy,
                                        floor.std_phi * floor.std_phi);
    if (!g.cov.allFinite() || !std::isfinite(g.mean.x) || !std::isfinite(g.mean.y) ||
        !std::isfinite(g.mean.phi))
        throw std::runtime_error("odometry with a non-finite increment or covariance");
    const Eigen::LLT<Eigen::Matrix3d> llt(g.cov);
    if (llt.info() != Eigen::Success)
        throw std::runtime_error("odometry covariance is not positive definite");
    g.L = llt.matrixL();
    return g;
}

Eigen::Vector3d drawGaussian(mrpt::random::CRandomGenerator& rng, const Eigen::Matrix3d& L)
{
    Eigen::Vector3d n;
    for (int i = 0; i < 3; i++) n[i] = rng.drawGaussian1D_normalized();
    return L * n;
}

const std::vector<Eigen::Vector3d>& drawStandardNormals(mrpt::random::CRandomGenerator& rng,
                                                        size_t count,
                                                        std::vector<Eigen::Vector3d>& n)
{
    n.resize(count);
    for (auto& v : n)
        for (int i = 0; i < 3; i++) v[i] = rng.drawGaussian1D_normalized();
    return n;
}

}  // namespace mrpt_vslam::core
