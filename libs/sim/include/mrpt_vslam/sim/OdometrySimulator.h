#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/random/RandomGenerators.h>

namespace mrpt_vslam::sim {

/** Noisy wheel odometry: each true pose increment Δ (robot frame) becomes a reading
 *
 *     Δ' = Δ + L·z,  z ~ N(0, I₃),  L·Lᵀ = Σ(Δ)                       (model noise)
 *     Δ'.φ += drift·|Δ.xy|                                         (heading drift)
 *
 *  where Σ(Δ) is the covariance that MRPT's Gaussian motion model
 *  (`CActionRobotMovement2D::computeFromOdometry`, `mmGaussian`, parameters a1..a4, minStdXY,
 *  minStdPHI) assigns to Δ, so a filter that uses `motionModel()` has the noise model the data
 *  was drawn from. The drift is a constant bias per metre, its sign drawn once from the stream;
 *  it is not part of the Gaussian model (it stays below minStdPHI per frame). */
class OdometrySimulator : public mrpt::config::CLoadableOptions {
  public:
    /// @name Parameters (ini section [Odometry])
    /// @{
    double a1 = 0.03;           ///< [m/m] std of x, y per metre travelled
    double a2 = 0.005;          ///< [m/rad] std of x, y per radian turned
    double a3 = 0.005;          ///< [rad/m] std of φ per metre travelled
    double a4 = 0.03;           ///< [rad/rad] std of φ per radian turned
    double minStdXY = 0.005;    ///< [m] std of x, y added to every increment
    double minStdPHI = 0.0035;  ///< [rad] std of φ added to every increment (ini: minStdPHI_deg)
    double heading_drift =
        0.0035;  ///< [rad/m] heading bias magnitude (ini: heading_drift_deg_per_m)
    /// @}

    /// Seeds the generator and draws the sign of the heading drift.
    void reset(uint32_t seed);
    /// One odometry reading for the true increment `true_increment`.
    mrpt::poses::CPose2D simulateIncrement(const mrpt::poses::CPose2D& true_increment);
    /// Signed heading drift [rad/m] in use since reset().
    double signedHeadingDrift() const { return m_signed_drift; }

    /// The MRPT Gaussian motion model with these parameters (what filters should use).
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions motionModel() const;

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                            const std::string& section) override;

  private:
    mrpt::random::CRandomGenerator m_rng;
    double m_signed_drift = 0;
};

}  // namespace mrpt_vslam::sim
