// Range-bearing input of the multi-robot filter (`<ROBOT>_RB`): the measurement in the robot
// frame against closed forms, bad measurements, association without descriptors (smallest D),
// identity bookkeeping, and the team filter on a synthetic planar world with hidden identities.
#include <gtest/gtest.h>
#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/multirobot/CMultiRobotVisualSLAM.h>
#include <mrpt_vslam/multirobot/LandmarkIdentityTally.h>
#include <mrpt_vslam/test/SyntheticTeamWorld.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <iostream>

using namespace mrpt_vslam::multirobot;

namespace {
mrpt::obs::CObservationBearingRange observation(
    std::initializer_list<std::array<double, 3>> range_bearing_id)
{
    mrpt::obs::CObservationBearingRange obs;
    obs.sensorLabel = "R1_RB";
    for (const auto& [r, b, id] : range_bearing_id) {
        mrpt::obs::CObservationBearingRange::TMeasurement m;
        m.range = static_cast<float>(r);
        m.yaw = static_cast<float>(b);
        m.pitch = 0;
        m.landmarkID = static_cast<int32_t>(id);
        obs.sensedData.push_back(m);
    }
    return obs;
}

/// The message with which measurementsFromBearingRange() refuses `obs`, or "accepted".
std::string refusalOf(const mrpt::obs::CObservationBearingRange& obs,
                      const TRangeBearingNoise& noise)
{
    try {
        measurementsFromBearingRange(obs, noise);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "accepted";
}
}  // namespace

TEST(RangeBearingMeasurement, PointAndCovarianceMatchTheClosedForm)
{
    TRangeBearingNoise noise;
    noise.std_range = 0.1;
    noise.std_bearing = 0.05;
    noise.std_height = 0.02;
    auto obs = observation({{2.0, 0.5, 7}});
    obs.sensorLocationOnRobot = mrpt::poses::CPose3D(0.1, -0.2, 0.3, M_PI / 2, 0, 0);
    const auto z = measurementsFromBearingRange(obs, noise);
    ASSERT_EQ(z.size(), 1u);
    const double r = 2.0, b = static_cast<float>(0.5);
    // sensor frame (r cos b, r sin b, 0) turned by 90° and moved by (0.1, -0.2, 0.3)
    EXPECT_NEAR(z[0].z.x(), 0.1 - r * std::sin(b), 1e-6);
    EXPECT_NEAR(z[0].z.y(), -0.2 + r * std::cos(b), 1e-6);
    EXPECT_NEAR(z[0].z.z(), 0.3, 1e-12);
    // in the sensor frame: radial variance σ_r², tangential (r σ_b)²; the turn swaps them
    const double radial = 0.01, tangential = r * r * 0.0025;
    const Eigen::Vector2d u_radial(-std::sin(b), std::cos(b)),
        u_tangent(-std::cos(b), -std::sin(b));
    const Eigen::Matrix2d expected =
        radial * u_radial * u_radial.transpose() + tangential * u_tangent * u_tangent.transpose();
    EXPECT_LT((z[0].R.topLeftCorner<2, 2>() - expected).norm(), 1e-9);
    EXPECT_NEAR(z[0].R(2, 2), 0.0004, 1e-12);
    EXPECT_NEAR(z[0].R(0, 2), 0, 1e-12);
    EXPECT_EQ(z[0].track_id, 7);
    EXPECT_NEAR(z[0].depth, 2.0, 1e-12);
}

TEST(RangeBearingMeasurement, BadMeasurementsNameTheLabel)
{
    const TRangeBearingNoise noise{0.1, 0.05, 0.01, {}, ""};
    for (const auto& obs : {observation({{std::nan(""), 0.1, -1}}),
                            observation({{1, std::nan(""), -1}}), observation({{2e5, 0.1, -1}})}) {
        const std::string refusal = refusalOf(obs, noise);
        EXPECT_NE(refusal.find("R1_RB"), std::string::npos) << refusal;
    }
    auto pitched = observation({{1, 0.1, -1}});
    pitched.sensedData[0].pitch = 0.2f;  // planar model: no pitch noise anywhere
    EXPECT_THROW(measurementsFromBearingRange(pitched, noise), std::runtime_error);
    // a range <= 0 (noise on a landmark at the sensor) is left out and counted
    size_t non_positive = 0;
    const auto kept = measurementsFromBearingRange(
        observation({{-0.1, 0.1, 1}, {2, 0.1, 2}, {0, 0, 3}}), noise, &non_positive);
    ASSERT_EQ(kept.size(), 1u);
    EXPECT_EQ(kept[0].track_id, 2);
    EXPECT_EQ(non_positive, 2u);
}

TEST(RangeBearingMeasurement, NoiseIsTheObservationsUnlessTheConfigSetsIt)
{
    auto obs = observation({{2.0, 0.0, -1}});
    // neither the observation nor the options give a range σ: refused, naming the label
    EXPECT_EQ(refusalOf(obs, TRangeBearingNoise()),
              "R1_RB: no usable range noise (sensor_std_range = 0): set it in the "
              "observations");
    TRangeBearingNoise fromIni;
    fromIni.config_keys = "S.rb";
    EXPECT_EQ(refusalOf(obs, fromIni),
              "R1_RB: no usable range noise (sensor_std_range = 0): set it in the "
              "observations, or S.rb_std_range in the config");
    obs.sensor_std_range = 0.3f;
    obs.sensor_std_yaw = 0.02f;
    const auto own = measurementsFromBearingRange(obs, TRangeBearingNoise());
    ASSERT_EQ(own.size(), 1u);
    // bearing 0 at 2 m: σ_x = σ_r, σ_y = r σ_b
    EXPECT_NEAR(own[0].R(0, 0), 0.09, 1e-6);
    EXPECT_NEAR(own[0].R(1, 1), 4 * 0.0004, 1e-6);
    TRangeBearingNoise set;
    set.std_range = 0.1;
    const auto overridden = measurementsFromBearingRange(obs, set);
    EXPECT_NEAR(overridden[0].R(0, 0), 0.01, 1e-9);
    EXPECT_NEAR(overridden[0].R(1, 1), 4 * 0.0004, 1e-6);  // still the observation's σ_b
}

// With validCovariances MRPT stores a covariance per measurement and no sensor_std_* (a rawlog
// then reads them as 0): the measurement's own is used, each σ the config sets replacing its row.
TEST(RangeBearingMeasurement, PerMeasurementCovariancesAreUsed)
{
    auto obs = observation({{2.0, 0.0, 1}, {3.0, M_PI / 2, 2}});
    obs.validCovariances = true;
    obs.sensedData[0].covariance.setDiagonal(std::vector<double>{0.09, 0.0004, 0});
    obs.sensedData[1].covariance.setDiagonal(std::vector<double>{0.01, 0.0009, 0});
    const auto own = measurementsFromBearingRange(obs, TRangeBearingNoise());
    ASSERT_EQ(own.size(), 2u);
    // bearing 0 at 2 m: σ_x = σ_r, σ_y = r σ_b; bearing 90° at 3 m: σ_y = σ_r, σ_x = r σ_b
    EXPECT_NEAR(own[0].R(0, 0), 0.09, 1e-9);
    EXPECT_NEAR(own[0].R(1, 1), 4 * 0.0004, 1e-9);
    EXPECT_NEAR(own[1].R(1, 1), 0.01, 1e-9);
    EXPECT_NEAR(own[1].R(0, 0), 9 * 0.0009, 1e-9);
    EXPECT_NEAR(own[0].R(2, 2), 0.01 * 0.01, 1e-12);  // planar: the height's σ

    // a correlation of range and bearing is kept: R = J S Jᵀ
    obs.sensedData[0].covariance(0, 1) = obs.sensedData[0].covariance(1, 0) = 0.005;
    EXPECT_NEAR(measurementsFromBearingRange(obs, TRangeBearingNoise())[0].R(0, 1), 2 * 0.005,
                1e-9);

    TRangeBearingNoise set;
    set.std_range = 0.1;
    const auto overridden = measurementsFromBearingRange(obs, set);
    EXPECT_NEAR(overridden[0].R(0, 0), 0.01, 1e-9);
    EXPECT_NEAR(overridden[0].R(0, 1), 0, 1e-12);          // its row replaced
    EXPECT_NEAR(overridden[0].R(1, 1), 4 * 0.0004, 1e-9);  // still the measurement's σ_b

    obs.sensedData[1].covariance(1, 1) = 0;
    set.config_keys = "S.rb";
    EXPECT_EQ(refusalOf(obs, set),
              "R1_RB: measurement of landmark 2 has a covariance without usable noise "
              "(variances of range, bearing, pitch: 0.01, 0, 0): set it in the "
              "observations, or S.rb_std_* in the config");
    obs.sensedData[1].covariance(1, 1) = 0.0009;
    obs.sensedData[1].covariance(0, 1) = obs.sensedData[1].covariance(1, 0) = 0.01;  // |ρ| > 1
    EXPECT_EQ(refusalOf(obs, TRangeBearingNoise()),
              "R1_RB: measurement of landmark 2 has a covariance that is not symmetric "
              "positive definite");
}

// A 3D landmark (pitch measured, MRPT's convention: positive downwards): the point and the
// covariance against finite differences of the spherical-to-Cartesian map.
TEST(RangeBearingMeasurement, SpatialModelMatchesTheSphericalCoordinates)
{
    const double r = 3.0, b = 0.4, p = -0.3;  // a landmark above the sensor
    auto obs = observation({{r, b, 4}});
    obs.sensedData[0].pitch = static_cast<float>(p);
    obs.sensorLocationOnRobot = mrpt::poses::CPose3D(0.2, 0, 0.5, 0.1, 0, 0);
    const TRangeBearingNoise noise{0.05, 0.01, 0.01, 0.02, ""};
    const auto z = measurementsFromBearingRange(obs, noise);
    ASSERT_EQ(z.size(), 1u);
    const float rf = static_cast<float>(r), bf = static_cast<float>(b), pf = static_cast<float>(p);
    const auto point = [&](double rr, double bb, double pp) {
        // the sensor's spherical coordinates of a point, inverted by MRPT itself
        mrpt::math::TPoint3D local(rr * std::cos(pp) * std::cos(bb),
                                   rr * std::cos(pp) * std::sin(bb), -rr * std::sin(pp));
        const auto robot = obs.sensorLocationOnRobot.composePoint(local);
        return Eigen::Vector3d(robot.x, robot.y, robot.z);
    };
    const Eigen::Vector3d expected = point(rf, bf, pf);
    EXPECT_LT((z[0].z - expected).norm(), 1e-6);
    double range = 0, yaw = 0, pitch = 0;  // and MRPT maps it back to the measurement
    obs.sensorLocationOnRobot.sphericalCoordinates({z[0].z.x(), z[0].z.y(), z[0].z.z()}, range, yaw,
                                                   pitch);
    EXPECT_NEAR(range, rf, 1e-6);
    EXPECT_NEAR(yaw, bf, 1e-6);
    EXPECT_NEAR(pitch, pf, 1e-6);
    const double h = 1e-6;
    Eigen::Matrix3d J;
    J.col(0) = (point(rf + h, bf, pf) - point(rf - h, bf, pf)) / (2 * h);
    J.col(1) = (point(rf, bf + h, pf) - point(rf, bf - h, pf)) / (2 * h);
    J.col(2) = (point(rf, bf, pf + h) - point(rf, bf, pf - h)) / (2 * h);
    const Eigen::Matrix3d C =
        J * Eigen::Vector3d(0.05 * 0.05, 0.01 * 0.01, 0.02 * 0.02).asDiagonal() * J.transpose();
    EXPECT_LT((z[0].R - C).norm(), 1e-8) << z[0].R << "\n" << C;
}

// Without descriptors every candidate has E = 0: the association takes the smallest D, not
// the first landmark created; the tally of its correspondences counts fused measurements of
// another identity.
TEST(RangeBearingMeasurement, WithoutDescriptorsTheNearestGatedLandmarkIsTaken)
{
    CVisualLandmarksMap map;
    map.insertionOptions.E0 = 0.25;
    TRangeBearingNoise noise;
    noise.std_range = 0.1;
    noise.std_bearing = 0.02;  // 6 cm across at 3 m: the gate D0 = 11.34 reaches 0.29 m
    std::vector<TCorrespondence> history;
    auto fuse = [&](double r, double b, int id) {
        const auto z = measurementsFromBearingRange(observation({{r, b, double(id)}}), noise);
        const auto in_map = toMapFrame(z[0], mrpt::math::TPose2D(0, 0, 0));
        auto candidates = map.findCandidates(z[0], in_map);
        const TFusionResult f = map.fuse(z[0], in_map, candidates, 0);
        history.push_back({0, f.id, z[0].track_id});
        return f;
    };
    const auto a = fuse(3.0, 0.00, 1);  // landmark A at (3, 0)
    const auto b = fuse(3.0, 0.12, 2);  // B at (2.98, 0.36): 0.36 m from A, outside its gate
    ASSERT_TRUE(a.created);
    ASSERT_TRUE(b.created);
    ASSERT_NE(a.id, b.id);
    // a point 0.225 m from A and 0.135 m from B: inside both gates, nearer B in D
    const auto c = fuse(3.0, 0.075, 2);
    EXPECT_FALSE(c.created);
    EXPECT_EQ(c.id, b.id);
    // the same point with identity 1: B again, counted as a conflict
    const auto d = fuse(3.0, 0.075, 1);
    EXPECT_EQ(d.id, b.id);
    const auto tally = TLandmarkIdentityTally::of(history, map);
    EXPECT_EQ(tally.landmarks_with_identity, 2u);
    EXPECT_EQ(tally.identities, 2u);
    EXPECT_EQ(tally.fused_measurements, 2u);
    EXPECT_EQ(tally.fused_with_another_identity, 1u);  // d: identity 1 into 2's landmark
}

// Two robots on overlapping circles in a 14 × 7 m room with 15 landmarks, range-bearing
// measurements (σ 0.05 m, 2°, field of view ±30°, up to 5 m), identities hidden, noisy
// odometry, M = 1000 (measured: RMSE 0.097 m vs odometry 0.433 m; 13 landmarks seen, 10
// mapped once, 17 map landmarks: a landmark first seen at 5 m across a 2° bearing error can
// be started again after a long gap; with M = 300, 0.28 m and 23 landmarks).
TEST(RangeBearingMeasurement, TeamFilterMapsAPlanarWorldWithHiddenIdentities)
{
    mrpt::random::CRandomGenerator rng(3);
    std::vector<Eigen::Vector2d> landmarks;
    for (int i = 0; i < 15; i++)
        landmarks.emplace_back(rng.drawUniform(-7.0, 7.0), rng.drawUniform(-3.5, 3.5));
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions model;
    model.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
    model.gaussianModel.a1 = 0.05f;
    model.gaussianModel.a2 = 0.005f;
    model.gaussianModel.a3 = 0.01f;
    model.gaussianModel.a4 = 0.05f;
    model.gaussianModel.minStdXY = 0.002f;
    model.gaussianModel.minStdPHI = static_cast<float>(mrpt::DEG2RAD(0.2));

    std::vector<mrpt::poses::CPose2D> truth{{-2, 0, 0}, {2, 0, M_PI}}, odo = truth;
    CMultiRobotVisualSLAM filter(CVisualLandmarksMap(), 1000, 5);
    filter.options.max_observations_per_robot = 10;
    filter.options.range_bearing_noise.std_range = 0.05;
    filter.options.range_bearing_noise.std_bearing = mrpt::DEG2RAD(2.0);
    filter.options.initial_std_xy = 0.01;
    filter.options.initial_std_phi = mrpt::DEG2RAD(0.2);
    filter.reset({truth[0].asTPose(), truth[1].asTPose()}, 0);
    mrpt::random::getRandomGenerator().randomize(5);
    mrpt::bayes::CParticleFilter pf;
    pf.m_options.PF_algorithm = mrpt::bayes::CParticleFilter::pfOptimalProposal;
    pf.m_options.BETA = 0.5;
    pf.setVerbosityLevel(mrpt::system::LVL_ERROR);

    const int steps = 400;  // 0.1 m and 2.5° a step: 3.5 laps of a 2.3 m circle each
    std::vector<std::vector<mrpt::poses::CPose2D>> true_path(2), odo_path(2);
    for (int t = 1; t <= steps; t++) {
        mrpt::obs::CActionCollection acts;
        mrpt::obs::CSensoryFrame sf;
        for (size_t k = 0; k < 2; k++) {
            const mrpt::poses::CPose2D delta(0.1, 0, mrpt::DEG2RAD(2.5));
            truth[k] = truth[k] + delta;
            const mrpt::poses::CPose2D noisy = mrpt_vslam::test::noisyOdometry(delta, model, rng);
            odo[k] = odo[k] + noisy;
            mrpt::obs::CActionRobotMovement2D act;
            act.timestamp = mrpt::Clock::fromDouble(t);
            act.computeFromOdometry(noisy, model);
            acts.insert(act);
            auto obs = mrpt::obs::CObservationBearingRange::Create();
            obs->sensorLabel = "R" + std::to_string(k + 1) + "_RB";
            for (const auto& l : landmarks) {
                const auto p = truth[k].inverseComposePoint(mrpt::math::TPoint2D(l.x(), l.y()));
                const double r = std::hypot(p.x, p.y), b = std::atan2(p.y, p.x);
                if (r > 5 || std::abs(b) > mrpt::DEG2RAD(30)) continue;
                mrpt::obs::CObservationBearingRange::TMeasurement m;
                m.range = static_cast<float>(r + 0.05 * rng.drawGaussian1D_normalized());
                m.yaw =
                    static_cast<float>(b + mrpt::DEG2RAD(2.0) * rng.drawGaussian1D_normalized());
                m.pitch = 0;
                m.landmarkID = -1;
                obs->sensedData.push_back(m);
            }
            sf.insert(obs);
        }
        pf.executeOn(filter, &acts, &sf);
        for (size_t k = 0; k < 2; k++) {
            true_path[k].push_back(truth[k]);
            odo_path[k].push_back(odo[k]);
        }
    }
    // the best particle's paths, as the app writes them
    double se = 0, se_odo = 0;
    for (size_t k = 0; k < 2; k++) {
        const auto path = CMultiRobotVisualSLAM::pathOf(filter.bestParticle(), k);
        ASSERT_EQ(path.size(), static_cast<size_t>(steps + 1));
        for (int t = 0; t < steps; t++) {
            const auto& x = path[t + 1].second;
            const auto& g = true_path[k][t];
            se += std::pow(std::hypot(x.x - g.x(), x.y - g.y()), 2);
            se_odo +=
                std::pow(std::hypot(odo_path[k][t].x() - g.x(), odo_path[k][t].y() - g.y()), 2);
        }
    }
    const double rmse = std::sqrt(se / (2 * steps)), rmse_odo = std::sqrt(se_odo / (2 * steps));
    EXPECT_LT(rmse, 0.4 * rmse_odo) << "odometry " << rmse_odo;
    EXPECT_LT(rmse, 0.15);
    // every landmark seen is mapped once: one map landmark within 0.5 m of each true one
    const auto& map = filter.bestParticle().map;
    size_t mapped_once = 0, seen = 0;
    for (const auto& l : landmarks) {
        size_t near = 0;
        map.landmarks().forEach([&](uint32_t, const TVisualLandmark& lm) {
            near += std::hypot(lm.mean.x() - l.x(), lm.mean.y() - l.y()) < 0.5 ? 1 : 0;
        });
        seen += near > 0 ? 1 : 0;
        mapped_once += near == 1 ? 1 : 0;
    }
    EXPECT_GE(seen, 12u);
    EXPECT_GE(mapped_once + 3, seen);
    EXPECT_LE(map.size(), seen + 5);
    std::cout << "RMSE " << rmse << " m, odometry " << rmse_odo << " m, landmarks " << map.size()
              << ", seen " << seen << ", mapped once " << mapped_once << "\n";
}
