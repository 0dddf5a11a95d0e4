#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/WaypointTrajectory.h>

#include <cmath>

#include "TestConfig.h"

using mrpt_vslam::sim::WaypointTrajectory;

namespace {

WaypointTrajectory hallTrajectory()
{
    WaypointTrajectory t;
    t.loadFromConfigFile(mrpt_vslam::sim::test::sportsHallConfig(), "Trajectory");
    return t;
}

double dist(const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b)
{
    return std::hypot(a.x - b.x, a.y - b.y);
}

}  // namespace

TEST(WaypointTrajectory, RespectsSpeedLimitsOfThePaper)
{
    const WaypointTrajectory t = hallTrajectory();
    const auto poses = t.generate(t.frames);
    ASSERT_EQ(poses.size(), 320u);
    double length = 0;
    for (size_t k = 1; k < poses.size(); k++) {
        const double step = dist(poses[k], poses[k - 1]);
        const double turn = std::abs(mrpt::math::wrapToPi(poses[k].phi - poses[k - 1].phi));
        EXPECT_LE(step, 0.30 + 1e-9) << "frame " << k;
        EXPECT_LE(turn, 0.52 + 1e-9) << "frame " << k;
        length += step;
    }
    // Gamallo et al. 2013, Sec. IV: "over 85 m" with 320 frames at 1 Hz.
    EXPECT_GT(length, 85.0);
    EXPECT_LT(length, 96.0);
}

TEST(WaypointTrajectory, ReturnsToTheStartAtFrames205And298And318)
{
    const WaypointTrajectory t = hallTrajectory();
    const auto poses = t.generate(t.frames);
    for (const int k : {205, 298, 318}) {
        EXPECT_LT(dist(poses[static_cast<size_t>(k)], poses[0]), 0.5) << "frame " << k;
        // And only then: 10 frames earlier the robot is still more than 1.5 m away.
        EXPECT_GT(dist(poses[static_cast<size_t>(k - 10)], poses[0]), 1.5) << "frame " << k - 10;
    }
}

TEST(WaypointTrajectory, StaysInsideTheHallArea)
{
    const WaypointTrajectory t = hallTrajectory();
    for (const auto& p : t.generate(t.frames)) {
        EXPECT_GE(p.x, 2.0);
        EXPECT_LE(p.x, 34.0);
        EXPECT_GE(p.y, -9.0);
        EXPECT_LE(p.y, 11.0);
    }
}

TEST(WaypointTrajectory, StopsOnTheLastWaypoint)
{
    mrpt::config::CConfigFileMemory cfg(
        "[T]\nstart_x = 0\nstart_y = 0\nstart_yaw_deg = 90\nwaypoints = 3 0\nframes = 60\n");
    WaypointTrajectory t;
    t.loadFromConfigFile(cfg, "T");
    const auto poses = t.generate(t.frames);
    EXPECT_EQ(poses.front(), mrpt::math::TPose2D(0, 0, M_PI / 2));
    EXPECT_NEAR(poses.back().x, 3.0, 0.01);
    EXPECT_NEAR(poses.back().y, 0.0, 0.3);
}

TEST(WaypointTrajectory, RejectsAnOddWaypointList)
{
    mrpt::config::CConfigFileMemory cfg("[T]\nwaypoints = 1 2 3\n");
    WaypointTrajectory t;
    EXPECT_THROW(t.loadFromConfigFile(cfg, "T"), mrpt_vslam::core::UsageError);
}
