#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>

#include <Eigen/LU>

#include "LightsTestUtils.h"

using mrpt::math::TPose2D;
using mrpt_vslam::omni_fastslam::CCeilingLightsMap;
using mrpt_vslam::omni_fastslam::TBearingMeasurement;
using mrpt_vslam::omni_fastslam::TLandmarkType;
using mrpt_vslam::omni_fastslam::TLightAssociation;
using mrpt_vslam::omni_fastslam::test::makeBearingObservation;

namespace {

/// Measurements of `lights` from `robot` with noise σ (none without rng).
std::vector<TBearingMeasurement> measure(const CCeilingLightsMap& map, const TPose2D& robot,
                                         const std::vector<Eigen::Vector3d>& lights, double sigma,
                                         mrpt::random::CRandomGenerator* rng = nullptr)
{
    return map.measurementsFromObservation(
        makeBearingObservation(map.measurementModel(), robot, lights, sigma, rng));
}

}  // namespace

TEST(CCeilingLightsMap, EkfUpdateShrinksCovarianceAndApproachesTruth)
{
    CCeilingLightsMap map;
    const Eigen::Vector3d light(2, 1, 6.5);
    const Eigen::Vector3d offset(0.3, -0.2, 0.4);
    map.addLandmark(light + offset, Eigen::Matrix3d::Identity() * 0.25);
    double prev_trace = map.landmarks()[0].cov.trace();
    for (int k = 0; k < 10; k++) {
        const TPose2D robot(-3 + 0.6 * k, 0.2 * k, 0.1 * k);
        const auto z = measure(map, robot, {light}, mrpt::DEG2RAD(0.5));
        const double log_w = map.updateLandmarks(z, robot, {0});
        EXPECT_TRUE(std::isfinite(log_w));
        const auto& lm = map.landmarks()[0];
        EXPECT_LT(lm.cov.trace(), prev_trace) << "step " << k;
        prev_trace = lm.cov.trace();
        EXPECT_LT((lm.cov - lm.cov.transpose()).cwiseAbs().maxCoeff(), 1e-15);
        EXPECT_GT(lm.cov.determinant(), 0);
        EXPECT_EQ(lm.counter, 2 + k);
    }
    EXPECT_LT((map.landmarks()[0].mean - light).norm(), 0.2 * offset.norm());
}

TEST(CCeilingLightsMap, LandmarkDeletedWhenCounterGoesNegative)
{
    CCeilingLightsMap map;
    map.addLandmark({1, 0, 6.5}, Eigen::Matrix3d::Identity() * 0.01, TLandmarkType::TypeI, 1);
    map.addLandmark({60, 0, 6.5}, Eigen::Matrix3d::Identity() * 0.01, TLandmarkType::TypeI, 0);
    const TPose2D robot(0, 0, 0);
    const std::vector<TBearingMeasurement> none;
    map.insertMeasurements(none, robot);  // in range, unseen: 1 → 0
    ASSERT_EQ(map.landmarks().size(), 2u);
    EXPECT_EQ(map.landmarks()[0].counter, 0);
    EXPECT_EQ(map.landmarks()[1].counter, 0);  // out of the perceptual range: unchanged
    map.insertMeasurements(none, robot);       // 0 → −1: deleted
    ASSERT_EQ(map.landmarks().size(), 1u);
    EXPECT_EQ(map.landmarks()[0].id, 1);
}

TEST(CCeilingLightsMap, UnseenLandmarkWeighsOneMinusPIn)
{
    CCeilingLightsMap map;
    map.likelihoodOptions.p_in = 0.75;
    map.addLandmark({1, 0, 6.5}, Eigen::Matrix3d::Identity() * 0.01);
    map.addLandmark({-1, 0, 6.5}, Eigen::Matrix3d::Identity() * 0.01, TLandmarkType::TypeII);
    const double log_w = map.updateLandmarks({}, TPose2D(0, 0, 0), {});
    EXPECT_NEAR(log_w, std::log(0.25), 1e-12);  // the type II landmark does not weigh
}

TEST(CCeilingLightsMap, CandidateDeletedAfterINotMisses)
{
    CCeilingLightsMap map;
    const TPose2D robot(0, 0, 0);
    const std::vector<Eigen::Vector3d> light{{1, 1, 6.5}};
    // Three sightings from the same pose: parallel rays, no cross-point, counter 3
    for (int k = 0; k < 3; k++) map.insertMeasurements(measure(map, robot, light, 0.01), robot);
    ASSERT_EQ(map.candidates().size(), 1u);
    EXPECT_EQ(map.candidates()[0].counter, 3);
    EXPECT_EQ(map.candidates()[0].nz, 3u);
    EXPECT_TRUE(map.candidates()[0].cross_points.empty());
    const std::vector<TBearingMeasurement> none;
    map.insertMeasurements(none, robot);  // I_not = 1: 3 → 2
    ASSERT_EQ(map.candidates().size(), 1u);
    EXPECT_EQ(map.candidates()[0].counter, 2);
    map.insertMeasurements(none, robot);  // I_not = 2: 2 → 0: deleted
    EXPECT_TRUE(map.candidates().empty());

    // With a fixed decrement of 1 it takes three misses
    CCeilingLightsMap fixed;
    fixed.insertionOptions.candidate_miss_decrement = 1;
    for (int k = 0; k < 3; k++) fixed.insertMeasurements(measure(fixed, robot, light, 0.01), robot);
    for (int k = 0; k < 2; k++) fixed.insertMeasurements(none, robot);
    EXPECT_EQ(fixed.candidates().size(), 1u);
    fixed.insertMeasurements(none, robot);
    EXPECT_TRUE(fixed.candidates().empty());
}

TEST(CCeilingLightsMap, CandidatePromotedNearTheTrueLight)
{
    CCeilingLightsMap map;  // the paper's initialization: the best cross-point with Σ0
    map.insertionOptions.refine_initialization = false;
    map.insertionOptions.sigma0_xx = map.insertionOptions.sigma0_yy =
        map.insertionOptions.sigma0_zz = 0.0025;
    const std::vector<Eigen::Vector3d> light{{3, 1, 6.5}};
    size_t promoted_at = 0;
    for (int k = 0; k < 14 && promoted_at == 0; k++) {
        const TPose2D robot(-2 + 0.5 * k, 0.1 * k, 0.05 * k);
        map.insertMeasurements(measure(map, robot, light, mrpt::DEG2RAD(0.2)), robot);
        if (!map.landmarks().empty()) promoted_at = static_cast<size_t>(k) + 1;
    }
    ASSERT_EQ(map.landmarks().size(), 1u) << map.asString();
    // NCROSS_valid = 5 needs at least 4 measurements, and ANG_min = 7° more than that here
    EXPECT_GE(promoted_at, 4u);
    EXPECT_TRUE(map.candidates().empty());
    const auto& lm = map.landmarks()[0];
    EXPECT_LT((lm.mean - light[0]).norm(), 0.02);
    EXPECT_EQ(lm.type, TLandmarkType::TypeI);
    EXPECT_EQ(lm.cov, Eigen::Matrix3d::Identity() * 0.0025);
    EXPECT_EQ(lm.counter, static_cast<int>(promoted_at));

    // Seen from farther than D_min: type II
    CCeilingLightsMap far_map;
    far_map.insertionOptions.d_min = 2.0;
    for (int k = 0; k < 14 && far_map.landmarks().empty(); k++) {
        const TPose2D robot(-2 + 0.5 * k, 0.1 * k, 0.05 * k);
        far_map.insertMeasurements(measure(far_map, robot, light, mrpt::DEG2RAD(0.2)), robot);
    }
    ASSERT_EQ(far_map.landmarks().size(), 1u);
    EXPECT_EQ(far_map.landmarks()[0].type, TLandmarkType::TypeII);
}

TEST(CCeilingLightsMap, TypeIiLandmarkBecomesTypeIWhenSeenFromClose)
{
    CCeilingLightsMap map;
    const Eigen::Vector3d light(0, 0, 6.5);
    map.addLandmark(light, Eigen::Matrix3d::Identity() * 0.01, TLandmarkType::TypeII);
    for (int k = 0; k < 3; k++) {
        const TPose2D robot(1 + 0.3 * k, 0, 0);
        EXPECT_EQ(map.landmarks()[0].type, TLandmarkType::TypeII);
        map.insertMeasurements(measure(map, robot, {light}, mrpt::DEG2RAD(0.2)), robot);
    }
    EXPECT_EQ(map.landmarks()[0].type, TLandmarkType::TypeI);  // NZ_min = 3 close sightings
}

TEST(CCeilingLightsMap, InconsistentMeasurementsAreNotPromoted)
{
    CCeilingLightsMap map;
    auto& rng = mrpt::random::getRandomGenerator();
    rng.randomize(7);
    // Force 12 measurements of random upward directions into one candidate
    for (int k = 0; k < 12; k++) {
        const TPose2D robot(0.5 * k, 0.3 * k, 0.2 * k);
        TBearingMeasurement m;
        m.z = {rng.drawUniform(-M_PI, M_PI), rng.drawUniform(0.2, 1.2)};
        m.Q = Eigen::Matrix2d::Identity() * std::pow(mrpt::DEG2RAD(1.0), 2);
        TLightAssociation assoc;
        assoc.landmark_of_measurement = {-1};
        assoc.candidate_of_measurement = {map.candidates().empty() ? -1 : 0};
        map.updateCandidates({m}, robot, assoc);
        map.updateLandmarksType();
    }
    EXPECT_TRUE(map.landmarks().empty());
    ASSERT_EQ(map.candidates().size(), 1u);
    EXPECT_EQ(map.candidates()[0].nz, 12u);
    EXPECT_EQ(map.candidates()[0].cross_points.size(), 12u * 11u / 2u);
    size_t n_valid = 0;
    for (const auto& x : map.candidates()[0].cross_points) n_valid += x.valid;
    EXPECT_LT(n_valid, map.insertionOptions.ncross_valid);
}

TEST(CCeilingLightsMap, CandidateKeepsAtMostMaxMeasurements)
{
    CCeilingLightsMap map;
    map.insertionOptions.max_candidate_measurements = 4;
    map.insertionOptions.ncross_valid = 100;  // never promote
    const std::vector<Eigen::Vector3d> light{{3, 1, 6.5}};
    for (int k = 0; k < 8; k++) {
        const TPose2D robot(-2 + 0.5 * k, 0, 0);
        map.insertMeasurements(measure(map, robot, light, mrpt::DEG2RAD(0.2)), robot);
    }
    ASSERT_EQ(map.candidates().size(), 1u);
    const auto& cand = map.candidates()[0];
    EXPECT_EQ(cand.nz, 8u);
    ASSERT_EQ(cand.observations.size(), 4u);
    EXPECT_EQ(cand.observations.front().step, 4u);
    EXPECT_EQ(cand.cross_points.size(), 6u);
    for (const auto& x : cand.cross_points) {
        EXPECT_GE(x.step_first, 4u);
        EXPECT_NEAR(x.sum_mahalanobis2, 0, 1e-6);  // noiseless rays meet at the light
    }
}

TEST(CCeilingLightsMap, SimulatedLoopMapsEveryLightOnce)
{
    CCeilingLightsMap map;
    const std::vector<Eigen::Vector3d> lights{
        {3, 3, 6.5}, {-3, 3, 6.5}, {3, -3, 6.5}, {-3, -3, 6.0}, {0.5, 0, 7.0}};
    auto& rng = mrpt::random::getRandomGenerator();
    rng.randomize(42);
    const int steps_per_lap = 60;
    for (int k = 0; k < 2 * steps_per_lap; k++) {
        const double a = 2 * M_PI * k / steps_per_lap;
        const TPose2D robot(2.5 * std::cos(a), 2.5 * std::sin(a), a + M_PI / 2);
        map.insertMeasurements(measure(map, robot, lights, mrpt::DEG2RAD(0.5), &rng), robot);
    }
    ASSERT_EQ(map.landmarks().size(), lights.size()) << map.asString();
    std::vector<bool> matched(lights.size(), false);
    for (const auto& lm : map.landmarks()) {
        size_t best = 0;
        for (size_t i = 1; i < lights.size(); i++)
            if ((lm.mean - lights[i]).norm() < (lm.mean - lights[best]).norm()) best = i;
        EXPECT_FALSE(matched[best]) << "light " << best << " mapped twice";
        matched[best] = true;
        EXPECT_LT((lm.mean - lights[best]).norm(), 0.2) << "light " << best;
        EXPECT_EQ(lm.type, TLandmarkType::TypeI);
    }
}
