#include <gtest/gtest.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt_vslam/sim/OdometrySimulator.h>

#include <Eigen/Core>

#include "TestConfig.h"

using mrpt_vslam::sim::OdometrySimulator;

TEST(OdometrySimulator, NoiseCovarianceIsTheMotionModelOfTheRawlog)
{
    OdometrySimulator odo;
    odo.loadFromConfigFile(mrpt_vslam::sim::test::sportsHallConfig(), "Odometry");
    odo.heading_drift = 0;
    odo.reset(11);
    const mrpt::poses::CPose2D truth(0.28, 0.02, 0.15);

    constexpr int kSamples = 40000;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (int i = 0; i < kSamples; i++) {
        const mrpt::poses::CPose2D r = odo.simulateIncrement(truth);
        const Eigen::Vector3d e(r.x() - truth.x(), r.y() - truth.y(),
                                mrpt::math::wrapToPi(r.phi() - truth.phi()));
        mean += e;
        second += e * e.transpose();
    }
    mean /= kSamples;
    const Eigen::Matrix3d cov = second / kSamples - mean * mean.transpose();

    mrpt::obs::CActionRobotMovement2D model;
    model.computeFromOdometry(truth, odo.motionModel());
    mrpt::math::CMatrixDouble33 expected;
    mrpt::poses::CPose2D m;
    model.poseChange->getCovarianceAndMean(expected, m);
    for (int i = 0; i < 3; i++) {
        EXPECT_NEAR(mean[i], 0.0, 4 * std::sqrt(expected(i, i) / kSamples));
        EXPECT_NEAR(cov(i, i) / expected(i, i), 1.0, 0.05) << "diagonal " << i;
    }
    // std of x, y ≈ minStdXY + a1·|d| + a2·|Δφ| (3 % of the distance plus small terms)
    const double sxy = odo.minStdXY + odo.a1 * std::hypot(0.28, 0.02) + odo.a2 * 0.15;
    EXPECT_NEAR(std::sqrt(cov(0, 0) + cov(1, 1)), std::sqrt(2.0) * sxy, 0.03 * sxy);
}

TEST(OdometrySimulator, HeadingDriftIsABiasPerMetre)
{
    OdometrySimulator odo;
    odo.heading_drift = mrpt::DEG2RAD(0.2);
    odo.reset(5);
    const double drift = odo.signedHeadingDrift();
    EXPECT_DOUBLE_EQ(std::abs(drift), mrpt::DEG2RAD(0.2));
    constexpr int kSamples = 20000;
    double sum = 0;
    for (int i = 0; i < kSamples; i++) sum += odo.simulateIncrement({0.3, 0, 0}).phi();
    // mean φ error = drift · 0.3 m, known to ±4 σ/√N
    const double sigma_phi = odo.minStdPHI + odo.a3 * 0.3;
    EXPECT_NEAR(sum / kSamples, drift * 0.3, 4 * sigma_phi / std::sqrt(kSamples));
}

TEST(OdometrySimulator, SameSeedSameReadings)
{
    OdometrySimulator a, b;
    a.reset(42);
    b.reset(42);
    for (int i = 0; i < 10; i++) {
        const auto ra = a.simulateIncrement({0.3, 0, 0.1});
        const auto rb = b.simulateIncrement({0.3, 0, 0.1});
        EXPECT_EQ(ra.x(), rb.x());
        EXPECT_EQ(ra.phi(), rb.phi());
    }
}
