#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/opengl/CEllipsoid3D.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/filesystem.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>

#include <limits>
#include <stdexcept>
#include <type_traits>

#include "LightsTestUtils.h"

using mrpt::math::TPose2D;
using mrpt_vslam::omni_fastslam::CCeilingLightsMap;
using mrpt_vslam::omni_fastslam::TAssociationMethod;
using mrpt_vslam::omni_fastslam::TLandmarkType;
using mrpt_vslam::omni_fastslam::TMeasurementModelKind;

namespace {

const char* kIni = R"ini(
[Mapping]
ceilingLightsMap_count = 1

[Mapping_ceilingLightsMap_00_creationOpts]
sensor_in_robot = [0.1 0 1.5 90 0 0]
sigma_phi_deg = 0.5
sigma_theta_deg = 0.75
max_theta_deg = 70
max_horizontal_distance = 12

[Mapping_ceilingLightsMap_00_insertOpts]
association_method = ml
nz_min = 4
ncross_valid = 6
ang_min_deg = 10
d_min = 6.5
sigma0_xx = 0.01
sigma0_yy = 0.02
sigma0_zz = 0.03
p_new_mahalanobis2 = 49
candidate_miss_decrement = 2
max_candidate_measurements = 15

[Mapping_ceilingLightsMap_00_likelihoodOpts]
p_in = 0.8
use_type_ii_landmarks = true

[Mapping_ceilingLightsMap_00_renderOpts]
draw_candidates = false
ellipsoid_quantiles = 2
)ini";

/// A map with two landmarks and one candidate carrying cross-points, built by insertions.
CCeilingLightsMap makePopulatedMap()
{
    CCeilingLightsMap map;
    map.addLandmark({1, 2, 6.5}, Eigen::Vector3d(0.01, 0.02, 0.03).asDiagonal());
    map.addLandmark({-3, 1, 6.0}, Eigen::Matrix3d::Identity() * 0.05, TLandmarkType::TypeII, 4);
    const auto model = map.measurementModel();
    const std::vector<Eigen::Vector3d> lights{{1, 2, 6.5}, {-3, 1, 6.0}, {4, -4, 6.5}};
    for (int k = 0; k < 3; k++) {
        const TPose2D robot(0.3 * k, 0, 0.1 * k);
        const auto obs =
            mrpt_vslam::omni_fastslam::test::makeBearingObservation(model, robot, lights, 0.01);
        map.insertMeasurements(map.measurementsFromObservation(obs), robot);
    }
    return map;
}

void expectSameContents(const CCeilingLightsMap& a, const CCeilingLightsMap& b)
{
    ASSERT_EQ(a.landmarks().size(), b.landmarks().size());
    for (size_t j = 0; j < a.landmarks().size(); j++) {
        EXPECT_EQ(a.landmarks()[j].id, b.landmarks()[j].id);
        EXPECT_EQ(a.landmarks()[j].mean, b.landmarks()[j].mean);
        EXPECT_EQ(a.landmarks()[j].cov, b.landmarks()[j].cov);
        EXPECT_EQ(a.landmarks()[j].counter, b.landmarks()[j].counter);
        EXPECT_EQ(a.landmarks()[j].type, b.landmarks()[j].type);
    }
    ASSERT_EQ(a.candidates().size(), b.candidates().size());
    for (size_t c = 0; c < a.candidates().size(); c++) {
        const auto &ca = a.candidates()[c], &cb = b.candidates()[c];
        EXPECT_EQ(ca.id, cb.id);
        EXPECT_EQ(ca.counter, cb.counter);
        EXPECT_EQ(ca.nz, cb.nz);
        ASSERT_EQ(ca.observations.size(), cb.observations.size());
        for (size_t i = 0; i < ca.observations.size(); i++) {
            EXPECT_EQ(ca.observations[i].measurement.z, cb.observations[i].measurement.z);
            EXPECT_EQ(ca.observations[i].measurement.Q, cb.observations[i].measurement.Q);
            EXPECT_EQ(ca.observations[i].robot_in_map, cb.observations[i].robot_in_map);
            EXPECT_EQ(ca.observations[i].step, cb.observations[i].step);
        }
        ASSERT_EQ(ca.cross_points.size(), cb.cross_points.size());
        for (size_t i = 0; i < ca.cross_points.size(); i++) {
            EXPECT_EQ(ca.cross_points[i].point, cb.cross_points[i].point);
            EXPECT_EQ(ca.cross_points[i].sum_log_prob, cb.cross_points[i].sum_log_prob);
            EXPECT_EQ(ca.cross_points[i].valid, cb.cross_points[i].valid);
        }
    }
    EXPECT_EQ(a.step(), b.step());
}

}  // namespace

TEST(CCeilingLightsMap, CopyAndMoveTraits)
{
    EXPECT_TRUE(std::is_copy_constructible_v<CCeilingLightsMap>);
    EXPECT_TRUE(std::is_copy_assignable_v<CCeilingLightsMap>);
    EXPECT_TRUE(std::is_move_constructible_v<CCeilingLightsMap>);
    EXPECT_TRUE(std::is_move_assignable_v<CCeilingLightsMap>);
}

TEST(CCeilingLightsMap, CreatedFromIniThroughMultiMetricMap)
{
    mrpt::config::CConfigFileMemory cfg(kIni);
    mrpt::maps::TSetOfMetricMapInitializers inits;
    inits.loadFromConfigFile(cfg, "Mapping");
    mrpt::maps::CMultiMetricMap mm(inits);
    ASSERT_EQ(mm.maps.size(), 1u);
    const auto map = mm.mapByClass<CCeilingLightsMap>();
    ASSERT_TRUE(map);

    const auto& s = map->sensorOptions;
    ASSERT_TRUE(s.sensor_in_robot.has_value());
    EXPECT_NEAR(s.sensor_in_robot->x(), 0.1, 1e-12);
    EXPECT_NEAR(s.sensor_in_robot->z(), 1.5, 1e-12);
    EXPECT_NEAR(s.sensor_in_robot->yaw(), M_PI / 2, 1e-12);
    EXPECT_NEAR(s.sigma_phi, 0.5 * M_PI / 180, 1e-12);
    EXPECT_NEAR(s.sigma_theta, 0.75 * M_PI / 180, 1e-12);
    EXPECT_NEAR(s.max_theta, 70 * M_PI / 180, 1e-12);
    EXPECT_EQ(s.max_horizontal_distance, 12);
    const auto& io = map->insertionOptions;
    EXPECT_EQ(io.association_method, TAssociationMethod::ML);
    EXPECT_EQ(io.nz_min, 4u);
    EXPECT_EQ(io.ncross_valid, 6u);
    EXPECT_NEAR(io.ang_min, 10 * M_PI / 180, 1e-12);
    EXPECT_EQ(io.d_min, 6.5);
    EXPECT_EQ(io.sigma0_xx, 0.01);
    EXPECT_EQ(io.sigma0_yy, 0.02);
    EXPECT_EQ(io.sigma0_zz, 0.03);
    EXPECT_EQ(io.p_new_mahalanobis2, 49);
    EXPECT_EQ(io.candidate_miss_decrement, 2u);
    EXPECT_EQ(io.max_candidate_measurements, 15u);
    EXPECT_EQ(map->likelihoodOptions.p_in, 0.8);
    EXPECT_TRUE(map->likelihoodOptions.use_type_ii_landmarks);
    EXPECT_FALSE(map->renderOptions.draw_candidates);
    EXPECT_EQ(map->renderOptions.ellipsoid_quantiles, 2);
}

// The paper's values, but Σ0 and the refined initialization (measured best, doc/omni-fastslam.md)
TEST(CCeilingLightsMap, DefaultsAreTheRecommendedValues)
{
    const CCeilingLightsMap map;
    const auto& io = map.insertionOptions;
    EXPECT_EQ(io.association_method, TAssociationMethod::Hungarian);
    EXPECT_EQ(io.nz_min, 3u);
    EXPECT_EQ(io.ncross_valid, 5u);
    EXPECT_NEAR(io.ang_min, 7 * M_PI / 180, 1e-15);
    EXPECT_EQ(io.d_min, 8.0);
    EXPECT_EQ(io.sigma0_xx, 0.5);
    EXPECT_EQ(io.sigma0_yy, 0.5);
    EXPECT_EQ(io.sigma0_zz, 0.5);
    EXPECT_TRUE(io.refine_initialization);
    EXPECT_EQ(io.p_new_mahalanobis2, 64);
    EXPECT_FALSE(map.sensorOptions.sensor_in_robot.has_value());  // the observations' own
}

// The camera pose comes from each observation, as in MRPT's own maps; a configured
// sensor_in_robot overrides it. Both survive serialization (particle copies go through it).
TEST(CCeilingLightsMap, CameraPoseIsTheObservationsUnlessConfigured)
{
    mrpt::obs::CObservationBearingRange obs;
    obs.sensorLocationOnRobot = mrpt::poses::CPose3D(0.1, 0, 1.0, 0, 0, 0);
    CCeilingLightsMap map;
    map.measurementsFromObservation(obs);
    EXPECT_NEAR(map.sensorPoseInUse().z(), 1.0, 1e-12);
    EXPECT_NEAR(map.measurementModel().sensorInRobot().x(), 0.1, 1e-12);

    CCeilingLightsMap configured;
    configured.sensorOptions.sensor_in_robot = mrpt::poses::CPose3D(0, 0, 1.8, 0, 0, 0);
    configured.measurementsFromObservation(obs);
    EXPECT_NEAR(configured.sensorPoseInUse().z(), 1.8, 1e-12);

    const CCeilingLightsMap back = mrpt_vslam::omni_fastslam::test::serializedCopy(map);
    const CCeilingLightsMap backConfigured =
        mrpt_vslam::omni_fastslam::test::serializedCopy(configured);
    EXPECT_FALSE(back.sensorOptions.sensor_in_robot.has_value());
    EXPECT_NEAR(back.sensorPoseInUse().z(), 1.0, 1e-12);
    ASSERT_TRUE(backConfigured.sensorOptions.sensor_in_robot.has_value());
    EXPECT_NEAR(backConfigured.sensorOptions.sensor_in_robot->z(), 1.8, 1e-12);
}

// The field of view and the reading range come from each observation (fieldOfView_yaw,
// minSensorDistance, maxSensorDistance) unless configured, each limit on its own; both survive
// serialization. A measurement outside the observation's own field of view, or an empty
// reading range, stops the run naming the key to set.
TEST(CCeilingLightsMap, SensorLimitsAreTheObservationsUnlessConfigured)
{
    mrpt::obs::CObservationBearingRange obs;
    obs.fieldOfView_yaw = static_cast<float>(M_PI);
    obs.minSensorDistance = 0.5f;
    obs.maxSensorDistance = 6.0f;
    CCeilingLightsMap map;
    const auto before = map.sensorLimitsInUse();  // before any observation: no limit
    EXPECT_EQ(before.max_abs_azimuth, M_PI);
    EXPECT_EQ(before.min_range, 0);
    EXPECT_EQ(before.max_range, 0);
    map.measurementsFromObservation(obs);
    EXPECT_NEAR(map.sensorLimitsInUse().max_abs_azimuth, M_PI / 2, 1e-6);
    EXPECT_NEAR(map.sensorLimitsInUse().min_range, 0.5, 1e-6);
    EXPECT_NEAR(map.sensorLimitsInUse().max_range, 6.0, 1e-6);
    EXPECT_FALSE(map.isWithinReadingRange({6.5, 0, 0}));
    EXPECT_TRUE(map.isWithinReadingRange({5.5, 0, 0}));
    EXPECT_FALSE(map.couldBeObserved({100 * M_PI / 180, 0.5}));

    CCeilingLightsMap configured;
    configured.sensorOptions.max_abs_azimuth = M_PI;
    configured.insertionOptions.max_cross_point_range = 8;
    configured.measurementsFromObservation(obs);
    EXPECT_EQ(configured.sensorLimitsInUse().max_abs_azimuth, M_PI);
    EXPECT_NEAR(configured.sensorLimitsInUse().min_range, 0.5, 1e-6);  // not set: observed
    EXPECT_EQ(configured.sensorLimitsInUse().max_range, 8);

    const CCeilingLightsMap back = mrpt_vslam::omni_fastslam::test::serializedCopy(map);
    const CCeilingLightsMap backConfigured =
        mrpt_vslam::omni_fastslam::test::serializedCopy(configured);
    EXPECT_FALSE(back.sensorOptions.max_abs_azimuth.has_value());
    EXPECT_FALSE(back.insertionOptions.max_cross_point_range.has_value());
    EXPECT_NEAR(back.sensorLimitsInUse().max_range, 6.0, 1e-6);
    EXPECT_NEAR(back.sensorLimitsInUse().max_abs_azimuth, M_PI / 2, 1e-6);
    EXPECT_EQ(backConfigured.sensorOptions.max_abs_azimuth, std::optional<double>(M_PI));
    EXPECT_EQ(backConfigured.insertionOptions.max_cross_point_range, std::optional<double>(8));
    EXPECT_FALSE(backConfigured.insertionOptions.min_cross_point_range.has_value());
    EXPECT_NEAR(backConfigured.sensorLimitsInUse().min_range, 0.5, 1e-6);

    const auto expectError = [](const CCeilingLightsMap& m,
                                const mrpt::obs::CObservationBearingRange& o,
                                const std::string& text) {
        try {
            m.measurementsFromObservation(o);
            ADD_FAILURE() << "accepted, expected: " << text;
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
        }
    };
    mrpt::obs::CObservationBearingRange behind = obs;
    mrpt::obs::CObservationBearingRange::TMeasurement m;
    m.yaw = static_cast<float>(135 * M_PI / 180);
    m.pitch = -0.5f;
    m.range = 1;
    behind.sensedData.push_back(m);
    expectError(map, behind, "outside the observation's field of view");
    expectError(map, behind, "set max_abs_azimuth_deg");
    EXPECT_NO_THROW(configured.measurementsFromObservation(behind));  // configured: all around

    CCeilingLightsMap nearBeyondFar;
    nearBeyondFar.insertionOptions.min_cross_point_range = 7;
    expectError(nearBeyondFar, obs, "set min_cross_point_range and max_cross_point_range");
}

TEST(CCeilingLightsMap, RejectsInvalidOptionsNamingTheKey)
{
    mrpt::config::CConfigFileMemory cfg("[s]\nnz_min = 1\n");
    CCeilingLightsMap::TInsertionOptions io;
    try {
        io.loadFromConfigFile(cfg, "s");
        FAIL() << "nz_min = 1 was accepted";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("nz_min"), std::string::npos) << e.what();
    }
    mrpt::config::CConfigFileMemory cfg2("[s]\np_in = 1\n");
    CCeilingLightsMap::TLikelihoodOptions lo;
    EXPECT_THROW(lo.loadFromConfigFile(cfg2, "s"), std::exception);
    // a pose without its brackets (MRPT's parser says only that the expression is malformed)
    // and one that is not finite
    for (const std::string pose : {"0 0 1.8 0 0 0", "[0 0 nan 0 0 0]"}) {
        mrpt::config::CConfigFileMemory cfg3("[s]\nsensor_in_robot = " + pose + "\n");
        CCeilingLightsMap::TSensorOptions so;
        try {
            so.loadFromConfigFile(cfg3, "s");
            ADD_FAILURE() << pose << " was accepted";
        } catch (const std::exception& e) {
            EXPECT_NE(std::string(e.what()).find(
                          "[s] sensor_in_robot: expected [x y z yaw pitch roll] (m, deg), got '" +
                          pose + "'"),
                      std::string::npos)
                << e.what();
        }
    }
}

TEST(CCeilingLightsMap, SerializationRoundTripThroughClassFactory)
{
    const CCeilingLightsMap map = makePopulatedMap();
    ASSERT_EQ(map.landmarks().size(), 2u);
    ASSERT_GE(map.candidates().size(), 1u);
    ASSERT_FALSE(map.candidates()[0].cross_points.empty());

    ASSERT_TRUE(mrpt::rtti::findRegisteredClass("mrpt_vslam::omni_fastslam::CCeilingLightsMap"));
    auto created = mrpt::rtti::classFactory("mrpt_vslam::omni_fastslam::CCeilingLightsMap");
    ASSERT_TRUE(std::dynamic_pointer_cast<CCeilingLightsMap>(created));

    CCeilingLightsMap options_source;
    options_source.insertionOptions.nz_min = 7;
    options_source.likelihoodOptions.p_in = 0.3;
    mrpt::io::CMemoryStream buf;
    auto arch = mrpt::serialization::archiveFrom(buf);
    arch << map << options_source;
    buf.Seek(0);
    mrpt::serialization::CSerializable::Ptr obj1, obj2;
    arch >> obj1 >> obj2;
    const auto back = std::dynamic_pointer_cast<CCeilingLightsMap>(obj1);
    ASSERT_TRUE(back);
    expectSameContents(map, *back);
    const auto back2 = std::dynamic_pointer_cast<CCeilingLightsMap>(obj2);
    ASSERT_TRUE(back2);
    EXPECT_EQ(back2->insertionOptions.nz_min, 7u);
    EXPECT_EQ(back2->likelihoodOptions.p_in, 0.3);
}

TEST(CCeilingLightsMap, MultiMetricMapCopyKeepsContents)
{
    mrpt::maps::CMultiMetricMap mm;
    mm.maps.push_back(std::make_shared<CCeilingLightsMap>(makePopulatedMap()));
    const mrpt::maps::CMultiMetricMap copy = mm;  // copies through serialization
    const auto a = mm.mapByClass<CCeilingLightsMap>();
    const auto b = copy.mapByClass<CCeilingLightsMap>();
    ASSERT_TRUE(a && b);
    EXPECT_NE(a.get(), b.get());
    expectSameContents(*a, *b);
}

TEST(CCeilingLightsMap, SavesMapTxtAsALandmarkFile)
{
    const CCeilingLightsMap map = makePopulatedMap();
    const std::string prefix = mrpt::system::getTempFileName();
    map.saveMetricMapRepresentationToFile(prefix);
    const auto file = mrpt_vslam::core::LandmarkFile::load(prefix + ".txt");
    ASSERT_EQ(file.size(), map.landmarks().size());
    for (size_t j = 0; j < file.size(); j++) {
        EXPECT_EQ(file.landmarks[j].id, map.landmarks()[j].id);
        EXPECT_NEAR(file.landmarks[j].position.x, map.landmarks()[j].mean.x(), 1e-6);
        EXPECT_NEAR(file.landmarks[j].position.z, map.landmarks()[j].mean.z(), 1e-6);
        ASSERT_TRUE(file.landmarks[j].has_cov);
        EXPECT_NEAR(file.landmarks[j].cov(1, 1), map.landmarks()[j].cov(1, 1), 1e-9);
    }
    mrpt::system::deleteFile(prefix + ".txt");
    mrpt::system::deleteFile(prefix);
}

TEST(CCeilingLightsMap, VisualizationHasAnEllipsoidPerLandmark)
{
    CCeilingLightsMap map = makePopulatedMap();
    mrpt::opengl::CSetOfObjects objs;
    map.getVisualizationInto(objs);
    size_t n_ellipsoids = 0;
    for (const auto& o : objs)
        if (std::dynamic_pointer_cast<mrpt::opengl::CEllipsoid3D>(o)) n_ellipsoids++;
    EXPECT_EQ(n_ellipsoids, map.landmarks().size());
    map.genericMapParams.enableSaveAs3DObject = false;
    mrpt::opengl::CSetOfObjects none;
    map.getVisualizationInto(none);
    EXPECT_EQ(none.size(), 0u);
    CCeilingLightsMap typed;
    typed.addLandmark({0, 0, 6}, Eigen::Matrix3d::Identity());
    typed.addLandmark({1, 0, 6}, Eigen::Matrix3d::Identity(), TLandmarkType::TypeII);
    EXPECT_NE(typed.asString().find("2 landmarks (1 type I, 1 type II), 0 candidates"),
              std::string::npos)
        << typed.asString();
}

TEST(CCeilingLightsMap, LikelihoodIsFiniteAndPeaksAtTheTruePose)
{
    CCeilingLightsMap map;
    const std::vector<Eigen::Vector3d> lights{
        {3, 3, 6.5}, {-3, 3, 6.5}, {3, -3, 6.5}, {-3, -3, 6.5}};
    for (const auto& l : lights) map.addLandmark(l, Eigen::Matrix3d::Identity() * 1e-3);
    const TPose2D truth(0.5, -0.2, 0.3);
    const auto obs = mrpt_vslam::omni_fastslam::test::makeBearingObservation(
        map.measurementModel(), truth, lights, mrpt::DEG2RAD(0.5));
    ASSERT_TRUE(map.canComputeObservationLikelihood(obs));
    auto ll = [&](const TPose2D& p) {
        return map.computeObservationLikelihood(obs,
                                                mrpt::poses::CPose3D(p.x, p.y, 0, p.phi, 0, 0));
    };
    const double at_truth = ll(truth);
    EXPECT_TRUE(std::isfinite(at_truth));
    EXPECT_GT(at_truth, ll({truth.x + 0.3, truth.y, truth.phi}));
    EXPECT_GT(at_truth, ll({truth.x, truth.y, truth.phi + 0.1}));
    // Far away: every measurement floored at P_new; still finite
    const double far = ll({truth.x + 40, truth.y - 40, 2.0});
    EXPECT_TRUE(std::isfinite(far));
    double floor_sum = 0;
    for (const auto& m : map.measurementsFromObservation(obs)) floor_sum += map.logPNew(m);
    EXPECT_NEAR(far, floor_sum, 1e-9);
    EXPECT_GT(at_truth, far);

    // Observations of other kinds are not handled
    const mrpt::obs::CObservationOdometry odo;
    EXPECT_FALSE(map.canComputeObservationLikelihood(odo));
    EXPECT_EQ(map.computeObservationLikelihood(odo, mrpt::poses::CPose3D()), 0.0);
}

TEST(CCeilingLightsMap, RejectsNonFiniteOrNegativeReadingsNamingTheSensor)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const auto messageFor = [](const mrpt::obs::CObservationBearingRange& obs) -> std::string {
        for (const auto model : {TMeasurementModelKind::Spherical, TMeasurementModelKind::Planar}) {
            CCeilingLightsMap map;
            map.sensorOptions.measurement_model = model;
            try {
                map.measurementsFromObservation(obs);
            } catch (const std::runtime_error& e) {
                return e.what();
            }
        }
        return "";
    };
    const auto reading = [](float yaw, float pitch, float range) {
        mrpt::obs::CObservationBearingRange obs;
        obs.sensorLabel = "CAM";
        obs.sensedData.resize(2);
        obs.sensedData[0].yaw = 0.1f;
        obs.sensedData[0].pitch = -1.0f;
        obs.sensedData[1].landmarkID = 7;
        obs.sensedData[1].yaw = yaw;
        obs.sensedData[1].pitch = pitch;
        obs.sensedData[1].range = range;
        return obs;
    };
    // ranges are not used: any value says "not measured"
    for (const float range : {0.0f, nan, inf, -1.0f})
        EXPECT_EQ(messageFor(reading(0.2f, -1.0f, range)), "") << range;
    for (const auto& obs : {reading(nan, -1.0f, 0), reading(0.2f, inf, 0)})
        EXPECT_EQ(messageFor(obs),
                  "CAM: measurement of landmark 7 has a non-finite bearing or pitch");

    auto covariances = reading(0.2f, -1.0f, 0);
    covariances.validCovariances = true;
    covariances.sensedData[1].covariance(1, 1) = -0.01;
    EXPECT_EQ(messageFor(covariances),
              "CAM: measurement of landmark 7 has a non-finite or negative covariance");
    covariances.sensedData[1].covariance(1, 1) = nan;
    EXPECT_EQ(messageFor(covariances),
              "CAM: measurement of landmark 7 has a non-finite or negative covariance");

    auto stds = reading(0.2f, -1.0f, 0);
    stds.sensor_std_yaw = nan;
    EXPECT_EQ(messageFor(stds), "CAM: sensor_std_yaw = nan: must be finite and >= 0");
    stds.sensor_std_yaw = 0.01f;
    stds.sensor_std_pitch = -1;
    EXPECT_EQ(messageFor(stds), "CAM: sensor_std_pitch = -1: must be finite and >= 0");
}

TEST(CCeilingLightsMap, SphericalModelRefusesReadingsAtOrBelowTheHorizon)
{
    // a planar range-bearing rawlog (pitch 0) given to the ceiling-lights map
    mrpt::obs::CObservationBearingRange obs;
    obs.sensedData.resize(2);
    obs.sensedData[0].pitch = -0.5f;
    obs.sensedData[1].landmarkID = 3;
    for (const float pitch : {0.0f, 0.2f}) {
        obs.sensedData[1].pitch = pitch;
        CCeilingLightsMap spherical;
        try {
            spherical.measurementsFromObservation(obs);
            ADD_FAILURE() << "pitch " << pitch << " accepted";
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()).rfind("CObservationBearingRange: measurement of "
                                                  "landmark 3 has pitch ",
                                                  0),
                      0u)
                << e.what();
            EXPECT_NE(std::string(e.what()).find("measurement_model = planar"), std::string::npos);
        }
        CCeilingLightsMap planar;
        planar.sensorOptions.measurement_model = TMeasurementModelKind::Planar;
        EXPECT_EQ(planar.measurementsFromObservation(obs).size(), 2u);
    }
}
