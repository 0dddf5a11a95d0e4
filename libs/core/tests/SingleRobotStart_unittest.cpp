// The start pose of a run from its ground truth: the true pose nearest the first step less that
// step's odometry, so that the first step lands on it (the ground truth's first pose where it
// begins with the rawlog, a later one where the rawlog is cut from a longer one); or from the
// config.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/SingleRobotStart.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <string>

using namespace mrpt_vslam::core;

namespace {
// poses at t = 100, 100.1, ..., 100.9 s: x = index, yaw = index / 10 rad
TumTrajectory tenPoses()
{
    TumTrajectory truth;
    for (int i = 0; i < 10; i++)
        truth.push_back(100 + 0.1 * i, mrpt::math::TPose3D(i, 2 * i, 0, 0.1 * i, 0, 0));
    return truth;
}

std::string errorOf(const TumTrajectory& truth, double t)
{
    try {
        groundTruthPoseAtStart(truth, t, {}, "NAME.groundtruth.tum", "[App] key");
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return {};
}

// The first step's pose, start ⊕ u, against the true pose `index` of `truth`
void expectFirstStepOn(const TumTrajectory& truth, double t, int index)
{
    const mrpt::math::TPose2D u(0.3, -0.1, 0.2);
    const auto start = groundTruthPoseAtStart(truth, t, u, "NAME.groundtruth.tum", "[App] key");
    const auto first = mrpt::poses::CPose2D(start) + mrpt::poses::CPose2D(u);
    const mrpt::math::TPose3D& expected = truth.poses[static_cast<size_t>(index)];
    EXPECT_NEAR(first.x(), expected.x, 1e-12) << t;
    EXPECT_NEAR(first.y(), expected.y, 1e-12) << t;
    EXPECT_NEAR(first.phi(), expected.yaw, 1e-12) << t;
}
}  // namespace

// A ground truth that begins with the rawlog: the first step lands on its first pose, also where
// the robot already moves at the first step (its odometry increment u is not zero)
TEST(SingleRobotStart, TheFirstStepOnTheFirstTruePoseWhereTheGroundTruthBeginsWithIt)
{
    for (const double t : {100.0, 100.04, 99.96}) expectFirstStepOn(tenPoses(), t, 0);
}

// A longer ground truth, begun before the rawlog: the first step lands on the true pose nearest
// to it
TEST(SingleRobotStart, TheFirstStepOnTheTruePoseNearestToIt)
{
    for (const auto& [t, index] : {std::pair{100.52, 5}, {100.48, 5}, {100.94, 9}})
        expectFirstStepOn(tenPoses(), t, index);
}

// MRPT's simul-landmarks stamps its steps microseconds apart: a rawlog cut from one starts from
// the true pose nearest its first step, not from the first one within the tolerance
TEST(SingleRobotStart, TheNearestTruePoseWhereStepsAreMicrosecondsApart)
{
    TumTrajectory truth;
    for (int i = 0; i < 10; i++)
        truth.push_back(100 + 15e-6 * i, mrpt::math::TPose3D(i, 2 * i, 0, 0.1 * i, 0, 0));
    for (const int index : {0, 1, 6}) expectFirstStepOn(truth, truth.timestamps[index], index);
}

TEST(SingleRobotStart, NoTruePoseNearTheFirstStepIsAnError)
{
    const TumTrajectory truth = tenPoses();
    EXPECT_EQ(errorOf(truth, 99.9),
              "NAME.groundtruth.tum: no true pose within 0.05 s of the rawlog's first step at "
              "99.900000 s (the ground truth runs from 100.000000 to 100.900000 s), so the run "
              "cannot start from it: give the rawlog its own ground truth, or set [App] key = "
              "false");
    EXPECT_NE(errorOf(truth, 101.0), "");
    EXPECT_EQ(errorOf(truth, 100.95), "");
}

TEST(SingleRobotStart, FromTheGroundTruthBesideTheRawlogOrFromTheConfig)
{
    const mrpt_vslam::test::ScratchFolder scratch("SingleRobotStart_unittest");
    const std::string rawlog = scratch.file("cut.rawlog");
    tenPoses().save(scratch.file("cut.groundtruth.tum"));
    for (const bool fromTruth : {true, false}) {
        mrpt::config::CConfigFileMemory cfg;
        cfg.write("App", "initial_pose_from_ground_truth", fromTruth);
        cfg.write("App", "initial_x", 7.5);
        cfg.write("App", "initial_yaw_deg", 90);
        SingleRobotStart start;
        start.loadFromConfig(cfg, "App");
        start.resolve(AppArguments(), rawlog);
        ASSERT_TRUE(start.groundTruth.has_value());
        const auto p = start.atFirstStep(100.7, {});
        EXPECT_DOUBLE_EQ(p.x, fromTruth ? 7 : 7.5) << fromTruth;
        EXPECT_NEAR(p.phi, fromTruth ? 0.7 : M_PI / 2, 1e-8) << fromTruth;  // TUM file: 9 digits
        if (fromTruth)
            EXPECT_THROW(start.atFirstStep(99, {}), std::runtime_error);
        else
            EXPECT_NO_THROW(start.atFirstStep(99, {}));
    }
}
