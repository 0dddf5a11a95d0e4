// CCeilingLightsMap with the planar measurement model (doc/omni-fastslam.md §12): measurements,
// likelihoods, perceptual range, the candidates' depth segment and the options' round trip.
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>

#include <cmath>
#include <optional>

#include "LightsTestUtils.h"

using Eigen::Vector3d;
using mrpt::math::TPose2D;
using mrpt_vslam::omni_fastslam::CCeilingLightsMap;
using mrpt_vslam::omni_fastslam::TBearingMeasurement;
using mrpt_vslam::omni_fastslam::TLightAssociation;
using mrpt_vslam::omni_fastslam::TMeasurementModelKind;

namespace {
constexpr double kDeg = M_PI / 180;

CCeilingLightsMap planarMap()
{
    CCeilingLightsMap map;
    map.sensorOptions.measurement_model = TMeasurementModelKind::Planar;
    map.sensorOptions.sensor_in_robot = mrpt::poses::CPose3D();
    map.sensorOptions.sigma_phi = 2 * kDeg;
    map.sensorOptions.max_abs_azimuth = 30 * kDeg;
    map.sensorOptions.max_horizontal_distance = 5;
    map.insertionOptions.min_cross_point_range = 1;
    map.insertionOptions.max_cross_point_range = 6;
    map.insertionOptions.p_new_mahalanobis2 = 16;
    return map;
}

/// The exact azimuth measurement of `landmark` from `robot`.
TBearingMeasurement azimuthOf(const CCeilingLightsMap& map, const Vector3d& landmark,
                              const TPose2D& robot, double offset = 0)
{
    TBearingMeasurement m;
    m.z = map.measurementModel().predict(landmark, robot);
    m.z[0] += offset;
    m.Q = Eigen::Vector2d(std::pow(2 * kDeg, 2), 1).asDiagonal();
    return m;
}

/// Inserts one measurement as a new candidate (or into candidate 0).
void addToCandidate(CCeilingLightsMap& map, const TBearingMeasurement& m, const TPose2D& robot)
{
    TLightAssociation assoc;
    assoc.landmark_of_measurement = {-1};
    assoc.candidate_of_measurement = {map.candidates().empty() ? -1 : 0};
    map.updateCandidates({m}, robot, assoc);
}
}  // namespace

TEST(CCeilingLightsMapPlanar, MeasurementsAreAzimuthsOnly)
{
    auto map = planarMap();
    mrpt::obs::CObservationBearingRange obs;
    obs.validCovariances = false;
    obs.sensor_std_yaw = static_cast<float>(3.5 * kDeg);
    obs.sensedData.resize(1);
    obs.sensedData[0].yaw = 0.3f;
    obs.sensedData[0].pitch = 0.2f;  // ignored
    obs.sensedData[0].range = 2.5f;  // ignored
    obs.sensedData[0].landmarkID = 12;
    const auto z = map.measurementsFromObservation(obs);
    ASSERT_EQ(z.size(), 1u);
    EXPECT_NEAR(z[0].z[0], 0.3, 1e-7);
    EXPECT_DOUBLE_EQ(z[0].z[1], M_PI / 2);
    EXPECT_NEAR(z[0].Q(0, 0), std::pow(3.5 * kDeg, 2), 1e-10);  // the observation's std wins
    EXPECT_EQ(z[0].hidden_id, 12);
    obs.sensor_std_yaw = 0;
    EXPECT_NEAR(map.measurementsFromObservation(obs)[0].Q(0, 0), std::pow(2 * kDeg, 2), 1e-12);
}

TEST(CCeilingLightsMapPlanar, LikelihoodsUseTheAzimuthAlone)
{
    const auto map = planarMap();
    Eigen::Matrix2d S;
    S << 0.01, 0, 0, 123;  // the θ entry is a placeholder
    const double s = 0.01, nu = 0.05;
    EXPECT_NEAR(map.measurementLogLikelihood({nu, 0}, S),
                -0.5 * std::log(2 * M_PI * s) - 0.5 * nu * nu / s, 1e-12);
    TBearingMeasurement m;
    m.Q = Eigen::Vector2d(s, 1).asDiagonal();
    EXPECT_NEAR(map.logPNew(m), -0.5 * std::log(2 * M_PI * s) - 8, 1e-12);
    // P_new sits at the gate: a measurement 4σ off has the likelihood of P_new
    EXPECT_NEAR(map.measurementLogLikelihood({4 * std::sqrt(s), 0}, S), map.logPNew(m), 1e-12);
}

TEST(CCeilingLightsMapPlanar, PerceptualRangeIsTheFieldOfView)
{
    const auto map = planarMap();
    const TPose2D robot(0, 0, 0);
    EXPECT_TRUE(map.isInPerceptualRange({3, 1, 0}, robot));     // 18°, 3.2 m
    EXPECT_FALSE(map.isInPerceptualRange({1, 1, 0}, robot));    // 45°
    EXPECT_FALSE(map.isInPerceptualRange({-3, 0, 0}, robot));   // behind
    EXPECT_FALSE(map.isInPerceptualRange({5.5, 0, 0}, robot));  // beyond 5 m
    EXPECT_TRUE(map.couldBeObserved({33 * kDeg, M_PI / 2}, 5 * kDeg));
    EXPECT_FALSE(map.couldBeObserved({36 * kDeg, M_PI / 2}, 5 * kDeg));
}

// A landmark nearer than min_cross_point_range or farther than max_cross_point_range is not one
// the camera reads: it is never associated, however well its azimuth agrees.
TEST(CCeilingLightsMapPlanar, LandmarksOutsideTheReadingRangeAreNotAssociated)
{
    auto map = planarMap();
    const TPose2D robot(1, 2, 0.5);
    const Eigen::Vector2d ahead(std::cos(0.6), std::sin(0.6));  // 0.1 rad left of the heading
    for (const double range : {0.5, 3.0, 7.0}) {
        const Eigen::Vector2d xy = Eigen::Vector2d(robot.x, robot.y) + range * ahead;
        map.addLandmark({xy.x(), xy.y(), 0}, 0.01 * Eigen::Matrix3d::Identity());
    }
    const auto z = azimuthOf(map, map.landmarks()[1].mean, robot);
    const Eigen::MatrixXd log_l = map.landmarkLogLikelihoods({z}, robot);
    EXPECT_TRUE(std::isinf(log_l(0, 0)) && log_l(0, 0) < 0);
    EXPECT_GT(log_l(0, 1), map.logPNew(z));
    EXPECT_TRUE(std::isinf(log_l(0, 2)) && log_l(0, 2) < 0);
    map.insertionOptions.min_cross_point_range = 0;  // no limits: all three agree
    map.insertionOptions.max_cross_point_range = 0;
    const Eigen::MatrixXd unlimited = map.landmarkLogLikelihoods({z}, robot);
    for (int j = 0; j < 3; j++) EXPECT_GT(unlimited(0, j), map.logPNew(z)) << j;
}

TEST(CCeilingLightsMapPlanar, CandidatePredictsTheSegmentThatAgreesWithItsMeasurements)
{
    auto map = planarMap();
    map.insertionOptions.ang_min = 40 * kDeg;  // no valid cross-point: the segment predicts
    const Vector3d landmark(3, 1.5, 0), other(4, 1.5, 0);
    // one reading: the whole segment [1, 6] m of its ray
    addToCandidate(map, azimuthOf(map, landmark, TPose2D(0, 0, 0)), TPose2D(0, 0, 0));
    ASSERT_EQ(map.candidates().size(), 1u);
    EXPECT_DOUBLE_EQ(map.candidates()[0].depth_min, 1);
    EXPECT_DOUBLE_EQ(map.candidates()[0].depth_max, 6);
    // a second one 1.5 m on: the depths (from there) within 4σ of the first reading
    addToCandidate(map, azimuthOf(map, landmark, TPose2D(1.5, 0, 0)), TPose2D(1.5, 0, 0));
    ASSERT_EQ(map.candidates().size(), 1u);
    const auto& cand = map.candidates()[0];
    ASSERT_EQ(cand.observations.size(), 2u);
    const double depth = (landmark - Vector3d(1.5, 0, 0)).norm();  // 2.12 m
    EXPECT_LE(cand.depth_min, depth);
    EXPECT_GE(cand.depth_max, depth);
    // closed form of the sampled ends: 1.09 m and 4.65 m (8° from the first reading)
    EXPECT_NEAR(cand.depth_min, 1.09, 0.03);
    EXPECT_NEAR(cand.depth_max, 4.65, 0.08);

    // from a third pose the segment spans azimuths 49.7°-70.7°: the landmark (56.3°) is on it,
    // a neighbour 1 m away (36.9°) is not
    const TPose2D third(2, 0, 0);
    const auto log_lik = map.candidateLogLikelihoods(
        {azimuthOf(map, landmark, third), azimuthOf(map, other, third)}, third);
    EXPECT_GT(log_lik(0, 0), log_lik(1, 0));
    TBearingMeasurement best = azimuthOf(map, landmark, third);
    EXPECT_NEAR(log_lik(0, 0), map.measurementLogLikelihood({0, 0}, best.Q + best.Q), 1e-9);
}

TEST(CCeilingLightsMapPlanar, MixedCandidateStartsOver)
{
    auto map = planarMap();
    const Vector3d a(4, 1.5, 0), b(4, -1.5, 0);
    addToCandidate(map, azimuthOf(map, a, TPose2D(0, 0, 0)), TPose2D(0, 0, 0));
    addToCandidate(map, azimuthOf(map, a, TPose2D(0.3, 0, 0)), TPose2D(0.3, 0, 0));
    ASSERT_EQ(map.candidates()[0].observations.size(), 2u);
    // a reading of another landmark, 40° away: no point of the ray agrees with all three
    addToCandidate(map, azimuthOf(map, b, TPose2D(0.6, 0, 0)), TPose2D(0.6, 0, 0));
    ASSERT_EQ(map.candidates().size(), 1u);
    const auto& cand = map.candidates()[0];
    EXPECT_EQ(cand.observations.size(), 1u);
    EXPECT_EQ(cand.nz, 1u);
    EXPECT_TRUE(cand.cross_points.empty());
    EXPECT_NEAR(cand.observations[0].measurement.z[0],
                map.measurementModel().predict(b, TPose2D(0.6, 0, 0))[0], 1e-12);
}

TEST(CCeilingLightsMapPlanar, SerializationKeepsThePlanarOptions)
{
    auto map = planarMap();
    map.insertionOptions.hit_increment = 3;
    addToCandidate(map, azimuthOf(map, {4, 1.5, 0}, TPose2D(0, 0, 0)), TPose2D(0, 0, 0));
    addToCandidate(map, azimuthOf(map, {4, 1.5, 0}, TPose2D(0.3, 0, 0)), TPose2D(0.3, 0, 0));
    const CCeilingLightsMap back = mrpt_vslam::omni_fastslam::test::serializedCopy(map);
    EXPECT_EQ(back.sensorOptions.measurement_model, TMeasurementModelKind::Planar);
    EXPECT_EQ(back.sensorOptions.max_abs_azimuth, std::optional<double>(30 * kDeg));
    EXPECT_EQ(back.insertionOptions.min_cross_point_range, std::optional<double>(1));
    EXPECT_EQ(back.insertionOptions.max_cross_point_range, std::optional<double>(6));
    EXPECT_EQ(back.insertionOptions.hit_increment, 3u);
    ASSERT_EQ(back.candidates().size(), 1u);
    EXPECT_DOUBLE_EQ(back.candidates()[0].depth_min, map.candidates()[0].depth_min);
    EXPECT_DOUBLE_EQ(back.candidates()[0].depth_max, map.candidates()[0].depth_max);
    EXPECT_EQ(back.candidates()[0].counter, 6);
}
