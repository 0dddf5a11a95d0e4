#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt_vslam/core/OdometryGaussian.h>

#include <cmath>
#include <limits>
#include <stdexcept>

using mrpt_vslam::core::TMotionNoiseFloor;
using mrpt_vslam::core::TOdometryGaussian;

namespace {
TOdometryGaussian fromOdometry(const mrpt::poses::CPose2D& mean,
                               const mrpt::math::CMatrixDouble33& cov,
                               const TMotionNoiseFloor& floor)
{
    mrpt::obs::CActionRobotMovement2D a;
    a.poseChange = mrpt::poses::CPosePDFGaussian::Create(mean, cov);
    return TOdometryGaussian::from(&a, floor);
}
}  // namespace

TEST(OdometryGaussian, AddsTheFloorAndFactorsTheCovariance)
{
    mrpt::math::CMatrixDouble33 cov;
    cov.setZero();
    cov(0, 0) = 0.01;
    cov(1, 1) = 0.04;
    cov(0, 1) = cov(1, 0) = 0.005;
    cov(2, 2) = 0.0025;
    const TMotionNoiseFloor floor{0.1, 0.05};
    const auto g = fromOdometry(mrpt::poses::CPose2D(1.0, -0.5, 0.3), cov, floor);
    EXPECT_DOUBLE_EQ(g.mean.x, 1.0);
    EXPECT_DOUBLE_EQ(g.mean.y, -0.5);
    EXPECT_DOUBLE_EQ(g.mean.phi, 0.3);
    EXPECT_NEAR(g.cov(0, 0), 0.01 + 0.01, 1e-15);
    EXPECT_NEAR(g.cov(1, 1), 0.04 + 0.01, 1e-15);
    EXPECT_NEAR(g.cov(2, 2), 0.0025 + 0.0025, 1e-15);
    EXPECT_NEAR(g.cov(0, 1), 0.005, 1e-15);
    EXPECT_LT((g.L * g.L.transpose() - g.cov).norm(), 1e-15);
    EXPECT_EQ(g.L(0, 1), 0.0);  // lower triangular

    // no odometry: no motion, the floor only
    const auto still = TOdometryGaussian::from(nullptr, floor);
    EXPECT_EQ(still.mean.x, 0.0);
    EXPECT_NEAR(still.cov(0, 0), 0.01, 1e-15);
    EXPECT_NEAR(still.cov(2, 2), 0.0025, 1e-15);
}

TEST(OdometryGaussian, RefusesNonFiniteOrIndefiniteOdometry)
{
    mrpt::math::CMatrixDouble33 cov;
    cov.setIdentity();
    const TMotionNoiseFloor floor;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(fromOdometry(mrpt::poses::CPose2D(nan, 0, 0), cov, floor), std::runtime_error);
    cov(1, 1) = std::numeric_limits<double>::infinity();
    EXPECT_THROW(fromOdometry(mrpt::poses::CPose2D(0, 0, 0), cov, floor), std::runtime_error);
    cov.setIdentity();
    cov(0, 0) = -1;
    EXPECT_THROW(fromOdometry(mrpt::poses::CPose2D(0, 0, 0), cov, floor), std::runtime_error);
}

TEST(OdometryGaussian, DrawsHaveTheCovarianceLLt)
{
    Eigen::Matrix3d L;
    L << 0.2, 0, 0, 0.1, 0.3, 0, -0.05, 0.02, 0.1;
    mrpt::random::CRandomGenerator rng(7);
    const int n = 200000;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
    for (int i = 0; i < n; i++) {
        const Eigen::Vector3d d = mrpt_vslam::core::drawGaussian(rng, L);
        sum += d;
        outer += d * d.transpose();
    }
    const Eigen::Vector3d mean = sum / n;
    const Eigen::Matrix3d cov = outer / n - mean * mean.transpose();
    EXPECT_LT(mean.norm(), 0.003);
    EXPECT_LT((cov - L * L.transpose()).cwiseAbs().maxCoeff(), 0.002);
    // the same seed, the same draws
    mrpt::random::CRandomGenerator a(3), b(3);
    EXPECT_EQ(mrpt_vslam::core::drawGaussian(a, L), mrpt_vslam::core::drawGaussian(b, L));
}

// Against MRPT's composition of Gaussian poses, an exact start (zero covariance) ⊕ the increment:
// its first-order covariance is J cov Jᵀ, J = ∂(a ⊕ b)/∂b.
TEST(OdometryGaussian, IncrementCovarianceInTheMapFrameIsMrptsComposition)
{
    mrpt::math::CMatrixDouble33 cov;
    cov.asEigen() << 4e-4, 1e-4, 2e-5, 1e-4, 9e-4, -3e-5, 2e-5, -3e-5, 1e-4;
    const mrpt::poses::CPose2D increment(0.3, -0.1, 0.2);
    for (const double phi : {0.0, 0.7, -2.5, M_PI}) {
        const mrpt::poses::CPosePDFGaussian start(mrpt::poses::CPose2D(1, 2, phi));
        const mrpt::poses::CPosePDFGaussian composed =
            start + mrpt::poses::CPosePDFGaussian(increment, cov);
        const Eigen::Matrix3d ours = mrpt_vslam::core::incrementCovInMapFrame(cov.asEigen(), phi);
        EXPECT_LT((ours - composed.cov.asEigen()).cwiseAbs().maxCoeff(), 1e-15) << "phi " << phi;
    }
}

TEST(OdometryGaussian, StandardNormalsAreTheSerialDrawsBitForBit)
{
    // drawStandardNormals() draws the generator's sequence itself: against a serial loop of
    // drawGaussian1D_normalized(), after an even or odd number of earlier draws (a value kept
    // from the last pair or not), for any count and thread count, and the draws after it
    for (const unsigned threads : {1u, 2u, 4u})
        for (const int before : {0, 1, 2, 3})
            for (const size_t count : {0, 1, 2, 3, 4, 7, 1001}) {
                mrpt::random::CRandomGenerator serial(11), bulk(11);
                for (int i = 0; i < before; i++)
                    ASSERT_EQ(serial.drawGaussian1D_normalized(), bulk.drawGaussian1D_normalized());
                std::vector<Eigen::Vector3d> n;
                mrpt_vslam::core::drawStandardNormals(bulk, count, n, threads);
                ASSERT_EQ(n.size(), count);
                for (size_t i = 0; i < count; i++)
                    for (int c = 0; c < 3; c++)
                        ASSERT_EQ(n[i][c], serial.drawGaussian1D_normalized())
                            << "threads " << threads << ", " << before << " before, count " << count
                            << ", value " << 3 * i + c;
                for (int i = 0; i < 3; i++)
                    ASSERT_EQ(bulk.drawGaussian1D_normalized(), serial.drawGaussian1D_normalized());
            }
}

TEST(MotionNoiseFloor, ReadsDegreesAndRefusesNonPositiveValues)
{
    TMotionNoiseFloor f;
    mrpt::config::CConfigFileMemory cfg;
    cfg.write("F", "min_motion_std_xy", 0.01);
    cfg.write("F", "min_motion_std_phi_deg", 0.5);
    f.loadFromConfigFile(cfg, "F");
    EXPECT_DOUBLE_EQ(f.std_xy, 0.01);
    EXPECT_NEAR(f.std_phi, 0.5 * M_PI / 180, 1e-15);

    mrpt::config::CConfigFileMemory saved;
    f.saveToConfigFile(saved, "F");
    TMotionNoiseFloor g;
    g.loadFromConfigFile(saved, "F");
    EXPECT_DOUBLE_EQ(g.std_xy, f.std_xy);
    EXPECT_NEAR(g.std_phi, f.std_phi, 1e-15);

    for (const char* bad : {"0", "-1", "nan"}) {
        mrpt::config::CConfigFileMemory c;
        c.write("F", "min_motion_std_phi_deg", std::string(bad));
        try {
            TMotionNoiseFloor h;
            h.loadFromConfigFile(c, "F");
            ADD_FAILURE() << bad << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_STREQ(e.what(), "[F] min_motion_std_phi_deg: must be > 0");
        }
    }
}
