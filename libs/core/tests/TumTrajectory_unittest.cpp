#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

using mrpt_vslam::core::TumTrajectory;
namespace fs = std::filesystem;

namespace {

const mrpt_vslam::test::ScratchFolder& scratch()
{
    static const mrpt_vslam::test::ScratchFolder folder("TumTrajectory_unittest");
    return folder;
}

std::string writeTemp(const std::string& name, const std::string& text)
{
    return scratch().write(name, text);
}

/// Message of the exception thrown by TumTrajectory::load(file), or "" if none.
std::string loadError(const std::string& file)
{
    try {
        TumTrajectory::load(file);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return {};
}

}  // namespace

TEST(TumTrajectory, SaveLoadRoundTrip)
{
    TumTrajectory traj;
    traj.push_back(1000.25, {1.5, -2.0, 0.0, mrpt::DEG2RAD(30.0), 0, 0});
    traj.push_back(1000.5, {1.75, -1.5, 0.1, mrpt::DEG2RAD(-170.0), 0, 0});
    traj.push_back(1001.0, {2.0, -1.0, 0.2, mrpt::DEG2RAD(90.0), mrpt::DEG2RAD(5.0), 0});
    const auto path = (scratch().path() / "rt.tum").string();
    traj.save(path, "round trip");
    EXPECT_FALSE(fs::exists(path + ".tmp"));
    const auto back = TumTrajectory::load(path);
    ASSERT_EQ(back.size(), 3u);
    for (size_t i = 0; i < 3; i++) {
        EXPECT_NEAR(back.timestamps[i], traj.timestamps[i], 1e-6);
        EXPECT_NEAR(back.poses[i].x, traj.poses[i].x, 1e-8);
        EXPECT_NEAR(back.poses[i].y, traj.poses[i].y, 1e-8);
        EXPECT_NEAR(back.poses[i].z, traj.poses[i].z, 1e-8);
        EXPECT_NEAR(back.poses[i].yaw, traj.poses[i].yaw, 1e-8);
        EXPECT_NEAR(back.poses[i].pitch, traj.poses[i].pitch, 1e-8);
    }
    fs::remove(path);
}

TEST(TumTrajectory, ReadsYawFromQuaternion)
{
    // Rotation of 90° about z: q = (0, 0, sin 45°, cos 45°).
    const auto path = writeTemp("yaw.tum",
                                "# t x y z qx qy qz qw\n\n"
                                "5.0 1 2 3 0 0 0.7071067811865476 0.7071067811865476\n");
    const auto traj = TumTrajectory::load(path);
    ASSERT_EQ(traj.size(), 1u);
    EXPECT_DOUBLE_EQ(traj.timestamps[0], 5.0);
    EXPECT_NEAR(traj.poses[0].yaw, M_PI / 2, 1e-12);
    EXPECT_NEAR(traj.poses[0].z, 3.0, 1e-12);
}

TEST(TumTrajectory, MalformedLineNamesFileAndLine)
{
    const auto path = writeTemp("bad.tum", "# header\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n");
    const auto msg = loadError(path);
    EXPECT_NE(msg.find(path + ":3:"), std::string::npos) << msg;
}

TEST(TumTrajectory, ExtraColumnIsAnError)
{
    const auto path = writeTemp("extra.tum", "1 0 0 0 0 0 0 1 7\n");
    EXPECT_NE(loadError(path).find(path + ":1:"), std::string::npos);
}

TEST(TumTrajectory, NonUnitQuaternionIsAnError)
{
    const auto path = writeTemp("quat.tum", "1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 2\n");
    const auto msg = loadError(path);
    EXPECT_NE(msg.find(path + ":2:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("quaternion"), std::string::npos) << msg;
}

TEST(TumTrajectory, NonIncreasingTimeIsAnError)
{
    const auto path = writeTemp("time.tum", "1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 1\n2 1 0 0 0 0 0 1\n");
    const auto msg = loadError(path);
    EXPECT_NE(msg.find(path + ":3:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("increasing"), std::string::npos) << msg;
}

TEST(TumTrajectory, NonFiniteValueIsAnError)
{
    const auto path = writeTemp("nan.tum", "1 nan 0 0 0 0 0 1\n");
    EXPECT_NE(loadError(path).find(path + ":1:"), std::string::npos);
}

TEST(TumTrajectory, MissingFileNamesTheFile)
{
    const auto path = (scratch().path() / "missing.tum").string();
    fs::remove(path);
    const auto msg = loadError(path);
    EXPECT_EQ(msg.rfind(path + ":", 0), 0u) << msg;
}

// A trajectory may be empty; a ground truth may not (nothing to start from or to score against).
TEST(TumTrajectory, AGroundTruthWithoutPosesIsAnError)
{
    const auto path = writeTemp("empty.tum", "# timestamp x y z qx qy qz qw\n");
    EXPECT_TRUE(TumTrajectory::load(path).empty());
    try {
        TumTrajectory::loadGroundTruth(path);
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), path + ": no poses");
    }
    EXPECT_EQ(TumTrajectory::loadGroundTruth(writeTemp("one.tum", "1 0 0 0 0 0 0 1\n")).size(), 1u);
}

TEST(TumTrajectory, NearestIndexWithinTolerance)
{
    TumTrajectory traj;
    for (double t : {1.0, 2.0, 3.0}) traj.push_back(t, {});
    EXPECT_EQ(traj.nearestIndex(1.0, 0.0), 0);
    EXPECT_EQ(traj.nearestIndex(1.4, 0.5), 0);
    EXPECT_EQ(traj.nearestIndex(1.6, 0.5), 1);
    EXPECT_EQ(traj.nearestIndex(2.96, 0.05), 2);
    EXPECT_EQ(traj.nearestIndex(3.2, 0.1), -1);
    EXPECT_EQ(traj.nearestIndex(0.5, 0.1), -1);
    EXPECT_EQ(traj.nearestIndex(2.5, 0.4), -1);
    EXPECT_EQ(TumTrajectory().nearestIndex(1.0, 10.0), -1);
}
