// The least squares after the run on the shipped hard sports hall (poor odometry, close
// lights): 10 particles keep a map rotated and scaled by the odometry's error; the smoothed path
// and lights are those of the ground truth within a few centimetres and decimetres.
#include <gtest/gtest.h>
#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/omni_fastslam/LightsPathSmoother.h>

#include <Eigen/Cholesky>
#include <cmath>

#include "LightsTestUtils.h"

using namespace mrpt_vslam;
using omni_fastslam::COmniFastSLAM;
using omni_fastslam::LightsPathSmoother;

namespace {
const std::string kPrefix =
    std::string(MRPT_VSLAM_SOURCE_DIR) + "/datasets/sports-hall-hard/hall-hard";

struct TRun {
    double filter_rmse = 0, smoothed_rmse = 0;
    double worst_light_error = 0;  ///< of the true lights, to the nearest smoothed light [m]
    size_t lights = 0;
    LightsPathSmoother::TResult result;
};

/// RMSE of a path's positions against the ground truth at the same timestamps.
double positionRmse(const std::vector<std::pair<double, mrpt::math::TPose2D>>& path,
                    const core::TumTrajectory& gt)
{
    double sum = 0;
    size_t n = 0;
    for (const auto& [t, p] : path)
        for (size_t i = 0; i < gt.timestamps.size(); i++)
            if (std::abs(gt.timestamps[i] - t) < 1e-6) {
                sum += std::pow(p.x - gt.poses[i].x, 2) + std::pow(p.y - gt.poses[i].y, 2);
                n++;
                break;
            }
    EXPECT_GT(n, path.size() / 2);
    return std::sqrt(sum / static_cast<double>(n));
}

TRun run(uint32_t seed, const LightsPathSmoother::TOptions& options)
{
    const auto gt = core::TumTrajectory::load(kPrefix + ".groundtruth.tum");
    COmniFastSLAM filter(omni_fastslam::test::hallMapTemplate(), 10, seed);
    mrpt::random::getRandomGenerator().randomize(seed);  // CParticleFilter's resampling draws
    LightsPathSmoother smoother;
    smoother.options = options;
    filter.setStepObserver(&smoother);
    mrpt::bayes::CParticleFilter pf;
    pf.m_options.PF_algorithm = mrpt::bayes::CParticleFilter::pfOptimalProposal;
    pf.m_options.resamplingMethod = mrpt::bayes::CParticleFilter::prSystematic;
    pf.setVerbosityLevel(mrpt::system::LVL_ERROR);
    const auto& p0 = gt.poses.front();
    filter.reset({p0.x, p0.y, p0.yaw}, gt.timestamps.front());
    core::RawlogReader reader(kPrefix + ".rawlog");
    for (core::TRawlogEntry e; reader.next(e);)
        if (e.actions && e.observations)
            pf.executeOn(filter, e.actions.get(), e.observations.get());

    TRun r;
    r.filter_rmse = positionRmse(COmniFastSLAM::pathOf(filter.bestParticle()), gt);
    r.result = smoother.smooth(filter.bestParticle());
    r.smoothed_rmse = positionRmse(r.result.path, gt);
    r.lights = r.result.map.landmarks().size();
    for (const auto& truth : core::LandmarkFile::load(kPrefix + ".landmarks.txt").landmarks) {
        double nearest = 1e9;
        for (const auto& lm : r.result.map.landmarks())
            nearest = std::min(
                nearest,
                (lm.mean - Eigen::Vector3d(truth.position.x, truth.position.y, truth.position.z))
                    .norm());
        r.worst_light_error = std::max(r.worst_light_error, nearest);
    }
    return r;
}
}  // namespace

TEST(LightsPathSmoother, RecoversThePathAndLightsTheFilterBent)
{
    const TRun r = run(1, LightsPathSmoother::TOptions());
    EXPECT_GT(r.filter_rmse, 0.5);  // the filter's own estimate: the map turned and scaled
    EXPECT_LT(r.smoothed_rmse, 0.2);
    EXPECT_EQ(r.lights, 16u);
    EXPECT_LT(r.worst_light_error, 0.3);
    EXPECT_LT(r.result.final_cost, r.result.initial_cost);
    EXPECT_GT(r.result.bearings, 2000u);
}

// Each round associates the bearings again at the smoothed poses: one round keeps the
// filter's associations, and with them the mistakes between the two close lights.
TEST(LightsPathSmoother, AssociatingAgainFixesTheFiltersMistakes)
{
    LightsPathSmoother::TOptions one;
    one.rounds = 1;
    const TRun first = run(2, one);
    const TRun again = run(2, LightsPathSmoother::TOptions());
    EXPECT_GT(first.worst_light_error, 0.5);
    EXPECT_LT(again.worst_light_error, 0.3);
    EXPECT_LT(again.smoothed_rmse, first.smoothed_rmse);
}

TEST(LightsPathSmoother, RefusesAPathItDidNotRecord)
{
    omni_fastslam::CCeilingLightsMap map;
    COmniFastSLAM filter(map, 2, 1);
    filter.reset({0, 0, 0}, 0);  // before the smoother was registered: no step recorded
    LightsPathSmoother smoother;
    filter.setStepObserver(&smoother);
    mrpt::bayes::CParticleFilter pf;
    pf.m_options.PF_algorithm = mrpt::bayes::CParticleFilter::pfOptimalProposal;
    pf.setVerbosityLevel(mrpt::system::LVL_ERROR);
    mrpt::obs::CActionCollection acts;
    mrpt::obs::CActionRobotMovement2D odo;
    odo.computeFromOdometry(mrpt::poses::CPose2D(0.1, 0, 0),
                            mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
    acts.insert(odo);
    mrpt::obs::CSensoryFrame sf;
    pf.executeOn(filter, &acts, &sf);
    smoother.onReset({0, 0, 0}, 0);  // the recorded run starts after the filter's
    EXPECT_THROW(smoother.smooth(filter.bestParticle()), std::logic_error);
}

// A light read from nearer than the camera reads one (min_cross_point_range): the least squares
// keep it at that range, where its bearings would put it nearer; without the limit it stays
// where they put it.
TEST(LightsPathSmoother, KeepsLightsBeyondTheNearestReadingRange)
{
    const Eigen::Vector3d light(2, 0.8, 0);  // the path passes 0.8 m from it
    const auto nearest = [&](double min_range) {
        omni_fastslam::TOmniFastSLAMParticle p;
        p.map.sensorOptions.measurement_model = omni_fastslam::TMeasurementModelKind::Planar;
        p.map.insertionOptions.min_cross_point_range = min_range;
        const int64_t id = p.map.addLandmark(light, 0.01 * Eigen::Matrix3d::Identity());
        const auto model = p.map.measurementModel();
        core::TOdometryGaussian u;
        u.mean = {0.2, 0, 0};
        u.cov = Eigen::Vector3d(1e-4, 1e-4, 1e-5).asDiagonal();
        u.L = u.cov.llt().matrixL();
        LightsPathSmoother smoother;
        smoother.options.rounds = 1;
        smoother.onReset({0, 0, 0}, 0);
        p.path.append(0.0, omni_fastslam::TOmniFastSLAMStep{{0, 0, 0}});
        for (int k = 1; k <= 20; k++) {
            const mrpt::math::TPose2D x(0.2 * k, 0, 0);
            omni_fastslam::TBearingMeasurement z;
            z.z = model.predict(light, x);
            z.Q = Eigen::Vector2d(std::pow(mrpt::DEG2RAD(3.0), 2), 1).asDiagonal();
            smoother.onStep(u, {z});
            p.path.append(0.2 * k, omni_fastslam::TOmniFastSLAMStep{x, {{id, -1, 0}}});
        }
        const auto r = smoother.smooth(p);
        EXPECT_EQ(r.lights_with_filter_covariance, 0u);
        const Eigen::Vector3d m = r.map.landmarks().at(0).mean;
        double d = 1e9;
        for (const auto& [t, x] : r.path) d = std::min(d, std::hypot(m.x() - x.x, m.y() - x.y));
        return d;
    };
    EXPECT_NEAR(nearest(0), 0.8, 0.01);
    EXPECT_GT(nearest(1), 0.97);
}

TEST(LightsPathSmoother, RefusesImpossibleOptionsNamingTheKey)
{
    const auto errorOf = [](const std::string& lines) -> std::string {
        mrpt::config::CConfigFileMemory ini("[S]\n" + lines);
        LightsPathSmoother::TOptions options;
        try {
            options.loadFromConfigFile(ini, "S");
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(errorOf(""), "") << "the defaults are valid";
    EXPECT_EQ(errorOf("max_iterations = 0"), "[S] max_iterations: must be 1 to 1000");
    EXPECT_EQ(errorOf("rounds = 101"), "[S] rounds: must be 1 to 100");
    EXPECT_EQ(errorOf("huber = nan"), "[S] huber: must be >= 0 (0: no Huber)");
    EXPECT_EQ(errorOf("merge_distance = -1"), "[S] merge_distance: must be >= 0 (0: no merging)");
}
