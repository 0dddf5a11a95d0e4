// The sensor checks' report in run.json.
#include <gtest/gtest.h>
#include <mrpt_vslam/core/RunReport.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "../src/SlamApp.h"

using namespace mrpt_vslam;

// A fit that is not finite (degenerate readings) is reported with null for those figures: the
// run's run.json stays valid JSON and the run is not lost; the finite figures are as fitted.
TEST(SensorPoseCheckReport, NonFiniteFiguresAreNull)
{
    core::RunReport report("test");
    apps::TSensorCheck check;
    check.sensor = "R1 SENSOR";
    check.pose.pairs = 10;
    check.pose.delta = Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0.25, 0);
    check.pose.cov = Eigen::Matrix3d::Identity() * 0.01;
    check.pose.cov(1, 1) = std::numeric_limits<double>::infinity();
    apps::reportSensorPoseChecks("test", "a landmark", "doc/multirobot.md", {check}, 0.5, report,
                                 true);
    const auto doc = nlohmann::json::parse(report.toJson());
    const auto& c = doc["results"]["sensor_pose_check"]["R1 SENSOR"];
    EXPECT_TRUE(c["dx_dy_m"][0].is_null()) << c;
    EXPECT_EQ(c["dx_dy_m"][1].get<double>(), 0.25) << c;
    EXPECT_EQ(c["std_dx_dy_m"][0].get<double>(), 0.1) << c;
    EXPECT_TRUE(c["std_dx_dy_m"][1].is_null()) << c;
    EXPECT_EQ(c["pairs"].get<int>(), 10) << c;
}
