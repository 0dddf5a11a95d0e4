// End-to-end accuracy of the FastSLAM 2.0 filter on the first frames of the shipped sports-hall
// dataset (bearings input), against its ground truth.
#include <gtest/gtest.h>
#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/LandmarkMetrics.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/omni_fastslam/COmniFastSLAM.h>

#include <cmath>

#include "LightsTestUtils.h"

using namespace mrpt_vslam;
using omni_fastslam::COmniFastSLAM;

namespace {
const std::string kPrefix = std::string(MRPT_VSLAM_SOURCE_DIR) + "/datasets/sports-hall/hall";

struct TRunResult {
    double final_position_error = 0, odometry_position_error = 0;
    std::vector<mrpt::math::TPoint3D> landmarks;
    size_t min_particles = 0, max_particles = 0;
};

TRunResult runFrames(size_t frames, mrpt::bayes::CParticleFilter::TParticleFilterAlgorithm alg,
                     uint32_t seed, bool adaptive = false, unsigned threads = 0)
{
    const auto gt = core::TumTrajectory::load(kPrefix + ".groundtruth.tum");
    COmniFastSLAM filter(omni_fastslam::test::hallMapTemplate(), 10, seed);
    filter.setThreadCount(threads);
    mrpt::random::getRandomGenerator().randomize(seed);
    mrpt::bayes::CParticleFilter pf;
    pf.m_options.PF_algorithm = alg;
    pf.m_options.resamplingMethod = mrpt::bayes::CParticleFilter::prSystematic;
    pf.m_options.adaptiveSampleSize = adaptive;
    pf.setVerbosityLevel(mrpt::system::LVL_ERROR);

    const auto& p0 = gt.poses.front();
    filter.reset({p0.x, p0.y, p0.yaw}, gt.timestamps.front());
    mrpt::poses::CPose2D odometry(p0.x, p0.y, p0.yaw);
    core::RawlogReader reader(kPrefix + ".rawlog");
    size_t n = 0;
    TRunResult r;
    r.min_particles = r.max_particles = filter.particlesCount();
    for (core::TRawlogEntry e; n < frames && reader.next(e);) {
        if (!e.actions || !e.observations) continue;
        pf.executeOn(filter, e.actions.get(), e.observations.get());
        r.min_particles = std::min(r.min_particles, filter.particlesCount());
        r.max_particles = std::max(r.max_particles, filter.particlesCount());
        odometry = odometry + e.actions->getBestMovementEstimation()->poseChange->getMeanVal();
        n++;
    }
    EXPECT_EQ(n, frames);
    const auto& best = filter.bestParticle();
    const auto& truth = gt.poses[frames - 1];
    r.final_position_error =
        std::hypot(best.robot_in_map.x - truth.x, best.robot_in_map.y - truth.y);
    r.odometry_position_error = std::hypot(odometry.x() - truth.x, odometry.y() - truth.y);
    for (const auto& lm : best.map.landmarks())
        r.landmarks.emplace_back(lm.mean.x(), lm.mean.y(), lm.mean.z());
    return r;
}

std::vector<mrpt::math::TPoint3D> trueLights()
{
    std::vector<mrpt::math::TPoint3D> pts;
    for (const auto& lm : core::LandmarkFile::load(kPrefix + ".landmarks.txt").landmarks)
        pts.push_back(lm.position);
    return pts;
}
}  // namespace

TEST(COmniFastSLAM, MapsTheFirstLoopOfTheSportsHall)
{
    // Frames 0-205: the robot closes its first loop at frame ~205.
    const auto r = runFrames(205, mrpt::bayes::CParticleFilter::pfOptimalProposal, 1);
    EXPECT_LT(r.final_position_error, 0.5);
    size_t close = 0;
    for (const auto& t : trueLights()) {
        double best = 1e9;
        for (const auto& e : r.landmarks) best = std::min(best, (t - e).norm());
        if (best < 1.0) close++;
    }
    EXPECT_GE(close, 12u) << "lights mapped within 1 m of a true light";
    EXPECT_LE(r.landmarks.size(), 14u) << "no duplicated lights";
}

TEST(COmniFastSLAM, IsReproducibleForASeed)
{
    const auto a = runFrames(40, mrpt::bayes::CParticleFilter::pfOptimalProposal, 7);
    const auto b = runFrames(40, mrpt::bayes::CParticleFilter::pfOptimalProposal, 7);
    EXPECT_EQ(a.final_position_error, b.final_position_error);
    EXPECT_EQ(a.landmarks.size(), b.landmarks.size());
}

TEST(COmniFastSLAM, StandardProposalRuns)
{
    const auto r = runFrames(40, mrpt::bayes::CParticleFilter::pfStandardProposal, 1);
    EXPECT_TRUE(std::isfinite(r.final_position_error));
    EXPECT_GT(r.landmarks.size(), 0u);
}

// KLD-sampling (adaptiveSampleSize): the particle count follows the spread, from the minimum
// (10) after the start to more when the odometry has spread the particles, and the run is
// the same for any thread count.
TEST(COmniFastSLAM, AdaptiveSampleSizeFollowsTheSpread)
{
    const auto one = runFrames(120, mrpt::bayes::CParticleFilter::pfOptimalProposal, 3, true, 1);
    EXPECT_EQ(one.min_particles, 10u);
    EXPECT_GT(one.max_particles, 30u);
    EXPECT_LT(one.final_position_error, 0.5);
    const auto two = runFrames(120, mrpt::bayes::CParticleFilter::pfOptimalProposal, 3, true, 2);
    EXPECT_EQ(one.final_position_error, two.final_position_error);
    EXPECT_EQ(one.max_particles, two.max_particles);
}

// A landmark nearer than the camera reads one (min_cross_point_range) is not associated with a
// bearing that points at it, in the FastSLAM 2.0 proposal and the update alike.
TEST(COmniFastSLAM, LandmarksNearerThanTheCameraReadsAreNotAssociated)
{
    const auto associated = [](double min_range) {
        omni_fastslam::CCeilingLightsMap map;
        map.sensorOptions.measurement_model = omni_fastslam::TMeasurementModelKind::Planar;
        map.sensorOptions.sensor_in_robot = mrpt::poses::CPose3D();
        map.insertionOptions.min_cross_point_range = min_range;
        map.addLandmark({0.6, 0.1, 0}, 1e-6 * Eigen::Matrix3d::Identity());
        COmniFastSLAM filter(map, 5, 1);
        filter.options.bearings_label.clear();  // every CObservationBearingRange
        mrpt::bayes::CParticleFilter pf;
        pf.m_options.PF_algorithm = mrpt::bayes::CParticleFilter::pfOptimalProposal;
        pf.setVerbosityLevel(mrpt::system::LVL_ERROR);
        filter.reset({0, 0, 0}, 0);
        mrpt::obs::CActionCollection acts;
        mrpt::obs::CActionRobotMovement2D odo;
        odo.computeFromOdometry(mrpt::poses::CPose2D(0.1, 0, 0),
                                mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
        acts.insert(odo);
        auto obs = mrpt::obs::CObservationBearingRange::Create();
        obs->sensedData.resize(1);
        obs->sensedData[0].yaw = static_cast<float>(std::atan2(0.1, 0.5));  // from (0.1, 0)
        obs->sensedData[0].range = 0.51f;
        obs->sensedData[0].landmarkID = -1;
        mrpt::obs::CSensoryFrame sf;
        sf.insert(obs);
        pf.executeOn(filter, &acts, &sf);
        return filter.lastStepStats.associated_to_landmarks;
    };
    EXPECT_EQ(associated(0), 5u);  // every particle
    EXPECT_EQ(associated(1), 0u);
}
