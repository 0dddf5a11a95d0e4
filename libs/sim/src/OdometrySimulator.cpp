#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt_vslam/sim/ConfigReading.h>
#include <mrpt_vslam/sim/OdometrySimulator.h>

#include <Eigen/Cholesky>

namespace mrpt_vslam::sim {

void OdometrySimulator::reset(uint32_t seed)
{
    m_rng.randomize(seed);
    m_signed_drift = m_rng.drawUniform(0.0, 1.0) < 0.5 ? -heading_drift : heading_drift;
}

mrpt::obs::CActionRobotMovement2D::TMotionModelOptions OdometrySimulator::motionModel() const
{
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions opts;
    opts.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
    opts.gaussianModel = {a1, a2, a3, a4, minStdXY, minStdPHI};
    return opts;
}

mrpt::poses::CPose2D OdometrySimulator::simulateIncrement(
    const mrpt::poses::CPose2D& true_increment)
{
    // Σ(Δ) as MRPT's Gaussian model computes it for this increment.
    mrpt::obs::CActionRobotMovement2D model;
    model.computeFromOdometry(true_increment, motionModel());
    mrpt::math::CMatrixDouble33 cov;
    mrpt::poses::CPose2D mean;
    model.poseChange->getCovarianceAndMean(cov, mean);

    const Eigen::Matrix3d L = cov.asEigen().llt().matrixL();
    Eigen::Vector3d z;
    for (int i = 0; i < 3; i++) z[i] = m_rng.drawGaussian1D_normalized();
    const Eigen::Vector3d e = L * z;
    const double dist = std::hypot(true_increment.x(), true_increment.y());
    return {true_increment.x() + e[0], true_increment.y() + e[1],
            mrpt::math::wrapToPi(true_increment.phi() + e[2] + m_signed_drift * dist)};
}

void OdometrySimulator::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                           const std::string& s)
{
    MRPT_LOAD_CONFIG_VAR(a1, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(a2, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(a3, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(a4, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(minStdXY, double, cfg, s);
    minStdPHI = readDegrees(cfg, s, "minStdPHI_deg", minStdPHI);
    heading_drift = readDegrees(cfg, s, "heading_drift_deg_per_m", heading_drift);
    checkConfig(a1 >= 0 && a2 >= 0 && a3 >= 0 && a4 >= 0, s, "a1..a4", ">= 0");
    checkConfig(minStdXY > 0, s, "minStdXY", "> 0");
    checkConfig(minStdPHI > 0, s, "minStdPHI_deg", "> 0");
    checkConfig(heading_drift >= 0, s, "heading_drift_deg_per_m", ">= 0");
}

}  // namespace mrpt_vslam::sim
