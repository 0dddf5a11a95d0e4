#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/CeilingLights.h>

#include "TestConfig.h"

using mrpt_vslam::sim::CeilingLights;

TEST(CeilingLights, FourteenLightsOnTheGridOfTableI)
{
    CeilingLights layout;
    layout.loadFromConfigFile(mrpt_vslam::sim::test::sportsHallConfig(), "Lights");
    const auto lights = layout.lights();
    ASSERT_EQ(lights.size(), 14u);
    // id, x, y (Gamallo et al. 2013, Table I; lights 1-4 at x = 4.5 m complete the grid)
    const double expected[14][3] = {
        {1, 4.5, -5.5},  {2, 4.5, -1},   {3, 4.5, 3.5},    {4, 4.5, 8},     {5, 13.5, -5.5},
        {6, 13.5, -1},   {7, 13.5, 3.5}, {8, 13.5, 8},     {9, 22.5, -5.5}, {10, 22.5, -1},
        {11, 22.5, 3.5}, {12, 22.5, 8},  {13, 31.5, -5.5}, {14, 31.5, -1}};
    for (size_t i = 0; i < 14; i++) {
        EXPECT_EQ(lights[i].id, static_cast<int>(expected[i][0]));
        EXPECT_DOUBLE_EQ(lights[i].position.x, expected[i][1]);
        EXPECT_DOUBLE_EQ(lights[i].position.y, expected[i][2]);
        EXPECT_DOUBLE_EQ(lights[i].position.z, 6.5);
    }
    EXPECT_GE(layout.radius, 0.2);
    EXPECT_LE(layout.radius, 0.25);
}

TEST(CeilingLights, OnlyLightsNearTheWindowsWashOutInsideTheIntervals)
{
    CeilingLights layout;
    layout.washout_x_min = 27;
    layout.washout_intervals = {40, 100, 200, 210};
    const auto lights = layout.lights();
    const auto& light13 = lights[12];
    const auto& light9 = lights[8];
    EXPECT_FALSE(layout.isWashedOut(light13, 39.9));
    EXPECT_TRUE(layout.isWashedOut(light13, 40.0));
    EXPECT_TRUE(layout.isWashedOut(light13, 99.9));
    EXPECT_FALSE(layout.isWashedOut(light13, 100.0));
    EXPECT_TRUE(layout.isWashedOut(light13, 205.0));
    EXPECT_FALSE(layout.isWashedOut(light9, 50.0));
}

TEST(CeilingLights, RejectsRowCountsThatDoNotMatchTheColumns)
{
    mrpt::config::CConfigFileMemory cfg("[L]\ncolumn_x = 1 2\ncolumn_rows = 4\n");
    CeilingLights layout;
    EXPECT_THROW(layout.loadFromConfigFile(cfg, "L"), mrpt_vslam::core::UsageError);
}

TEST(CeilingLights, ExtraLightsFollowTheGridAtItsHeight)
{
    mrpt::config::CConfigFileMemory cfg(
        "[L]\ncolumn_x = 1 2\nrow_y = 0 5\ncolumn_rows = 2 1\nheight = 4\n"
        "extra_lights = 1.5 0  2 6.2\n");
    CeilingLights layout;
    layout.loadFromConfigFile(cfg, "L");
    const auto lights = layout.lights();
    ASSERT_EQ(lights.size(), 5u);
    EXPECT_EQ(lights[3].id, 4);
    EXPECT_DOUBLE_EQ(lights[3].position.x, 1.5);
    EXPECT_DOUBLE_EQ(lights[3].position.y, 0);
    EXPECT_EQ(lights[4].id, 5);
    EXPECT_DOUBLE_EQ(lights[4].position.y, 6.2);
    EXPECT_DOUBLE_EQ(lights[4].position.z, 4);

    mrpt::config::CConfigFileMemory odd("[L]\nextra_lights = 1 2 3\n");
    EXPECT_THROW(layout.loadFromConfigFile(odd, "L"), mrpt_vslam::core::UsageError);
}
