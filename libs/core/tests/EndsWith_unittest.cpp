#include <gtest/gtest.h>
#include <mrpt_vslam/core/EndsWith.h>

using mrpt_vslam::core::endsWith;

TEST(EndsWith, ComparesTheLastCharacters)
{
    EXPECT_TRUE(endsWith("run.rawlog", ".rawlog"));
    EXPECT_TRUE(endsWith(".rawlog", ".rawlog"));
    EXPECT_TRUE(endsWith("R1_STEREO", "_STEREO"));
    EXPECT_TRUE(endsWith("x", ""));
    EXPECT_TRUE(endsWith("", ""));
    EXPECT_FALSE(endsWith("run.rawlog.gz", ".rawlog"));
    EXPECT_FALSE(endsWith("rawlog", ".rawlog"));
    EXPECT_FALSE(endsWith("run.RAWLOG", ".rawlog"));
    EXPECT_FALSE(endsWith("", "x"));
}
