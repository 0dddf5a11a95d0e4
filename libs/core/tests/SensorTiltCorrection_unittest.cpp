#include <gtest/gtest.h>
#include <mrpt_vslam/core/SensorTiltCorrection.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using mrpt_vslam::core::TPointReading;
using mrpt_vslam::core::TSensorTiltCorrection;

namespace {

/// R_c = R_y(pitch) R_x(roll), robot axes.
Eigen::Matrix3d tiltRotation(double pitch, double roll)
{
    return (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
        .toRotationMatrix();
}

/** A robot driving and turning on a plane among 60 points 0-2.5 m high, read within 1-6 m
 *  ahead by a sensor at s = (0.1, 0.05, 0.5) on it whose orientation is off by R_c of
 *  (`pitch`, `roll`): the readings are where the stated orientation puts them,
 *  s + R_cᵀ (q − s) for the point q in the robot frame. Noise σ_across across the stated ray
 *  and σ_along along it (a stereo camera's depth), drawn from each reading's covariance R;
 *  with `exact`, no noise drawn but R kept. Per point its readings. */
std::vector<std::vector<TPointReading>> pointReadings(double pitch, double roll,
                                                      double sigma_across, double sigma_along,
                                                      std::mt19937& rng, bool exact = false)
{
    std::uniform_real_distribution<double> x(-4, 12), y(-4, 4), z(0, 2.5);
    std::normal_distribution<double> n(0, 1);
    std::vector<Eigen::Vector3d> world;
    for (int i = 0; i < 60; i++) world.emplace_back(x(rng), y(rng), z(rng));
    const Eigen::Vector3d s(0.1, 0.05, 0.5);
    const Eigen::Matrix3d Rc = tiltRotation(pitch, roll);
    std::vector<std::vector<TPointReading>> points(world.size());
    double px = -4, py = 0, heading = 0;
    for (int k = 0; k < 60; k++) {
        const Eigen::Matrix3d Rz = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).matrix();
        for (size_t i = 0; i < world.size(); i++) {
            const Eigen::Vector3d q = Rz.transpose() * (world[i] - Eigen::Vector3d(px, py, 0));
            const double range = (q - s).norm();
            if (q.x() - s.x() < 0.5 || range < 1 || range > 6) continue;
            TPointReading r;
            r.z = s + Rc.transpose() * (q - s);
            const Eigen::Vector3d along = (r.z - s).normalized();
            r.R = sigma_across * sigma_across * Eigen::Matrix3d::Identity() +
                  (sigma_along * sigma_along - sigma_across * sigma_across) * along *
                      along.transpose();
            if (!exact) r.z += r.R.llt().matrixL() * Eigen::Vector3d(n(rng), n(rng), n(rng));
            points[i].push_back(r);
        }
        // 0.2 m ahead, turning left and right in turn
        px += 0.2 * std::cos(heading);
        py += 0.2 * std::sin(heading);
        heading += 0.2 * std::sin(0.25 * k);
    }
    return points;
}

}  // namespace

// Exact readings: the correction is the tilt, pitch and roll each alone and together.
TEST(SensorTiltCorrection, RecoversTheTiltOfExactReadings)
{
    std::mt19937 rng(1);
    for (const Eigen::Vector2d& tilt : {Eigen::Vector2d(0, 0), Eigen::Vector2d(0.05, 0),
                                        Eigen::Vector2d(0, -0.08), Eigen::Vector2d(-0.2, 0.15)}) {
        const auto points = pointReadings(tilt[0], tilt[1], 0.02, 0.02, rng, true);
        const auto c = TSensorTiltCorrection::estimate(points);
        EXPECT_NEAR(c.delta[0], tilt[0], 1e-6) << tilt.transpose();
        EXPECT_NEAR(c.delta[1], tilt[1], 1e-6) << tilt.transpose();
        EXPECT_EQ(c.outlier_readings, 0u);
        EXPECT_GT(c.points, 20u);
        EXPECT_GT(c.readings, 4 * c.points);
    }
}

// Noisy readings, their depth 15 times as noisy as across (a stereo camera a few metres from
// its points): over 30 worlds the estimates are not drawn off (with the variance of a height
// held fixed in the Jacobian, the mean error is 0.0034 rad on each angle and the normalised
// squared error 2.5) and their spread is the covariance's.
TEST(SensorTiltCorrection, NeitherDrawnToZeroNorOverconfidentOnNoisyReadings)
{
    std::mt19937 rng(2);
    const Eigen::Vector2d tilt(0.09, -0.07);  // 5.2° and −4.0°
    double normalisedSquares = 0;
    Eigen::Vector2d meanError = Eigen::Vector2d::Zero();
    constexpr int kWorlds = 30;
    for (int world = 0; world < kWorlds; world++) {
        const auto c =
            TSensorTiltCorrection::estimate(pointReadings(tilt[0], tilt[1], 0.02, 0.30, rng));
        const Eigen::Vector2d error = c.delta - tilt;
        meanError += error / kWorlds;
        normalisedSquares += error.dot(c.cov.inverse() * error);
        EXPECT_LT(std::sqrt(c.cov(0, 0)), 0.01) << "world " << world;
    }
    std::printf("mean error (%.4f, %.4f) rad, normalised squared error %.2f per component\n",
                meanError[0], meanError[1], normalisedSquares / (2 * kWorlds));
    EXPECT_LT(meanError.cwiseAbs().maxCoeff(), 0.002);
    EXPECT_GT(normalisedSquares / (2 * kWorlds), 0.5);
    EXPECT_LT(normalisedSquares / (2 * kWorlds), 2.0);
}

// A reading of another point, 0.5 m off in height among the readings of the point read most,
// moves the estimate by little: Huber.
TEST(SensorTiltCorrection, AWrongReadingHardlyMovesIt)
{
    std::mt19937 rng(3);
    auto points = pointReadings(0.03, 0.02, 0.02, 0.05, rng);
    const auto clean = TSensorTiltCorrection::estimate(points);
    auto& most = *std::max_element(points.begin(), points.end(), [](const auto& a, const auto& b) {
        return a.size() < b.size();
    });
    ASSERT_GT(most.size(), 8u);
    most[most.size() / 2].z.z() += 0.5;
    const auto wrong = TSensorTiltCorrection::estimate(points);
    EXPECT_EQ(wrong.outlier_readings, clean.outlier_readings + 1);
    EXPECT_LT((wrong.delta - clean.delta).norm(), 0.002);
    const auto plain = TSensorTiltCorrection::estimate(points, 0);
    EXPECT_GT((plain.delta - clean.delta).norm(), (wrong.delta - clean.delta).norm());
}

// Points read once tell nothing; none at all leaves the prior.
TEST(SensorTiltCorrection, PointsReadOnceAreLeftOut)
{
    std::vector<std::vector<TPointReading>> once(5, std::vector<TPointReading>(1));
    for (auto& p : once) p[0].R = Eigen::Matrix3d::Identity() * 1e-4;
    const auto c = TSensorTiltCorrection::estimate(once);
    EXPECT_EQ(c.points, 0u);
    EXPECT_EQ(c.readings, 0u);
    EXPECT_EQ(c.delta, Eigen::Vector2d::Zero());
    EXPECT_NEAR(c.cov(0, 0), M_PI * M_PI, 1e-9);
}
