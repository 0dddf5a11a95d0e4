#include <gtest/gtest.h>
#include <mrpt/version.h>
#include <mrpt_vslam/core/Version.h>

#include <cstdio>
#include <fstream>
#include <sstream>

TEST(Version, ProjectVersionIsTheOneInCMakeLists)
{
    std::ifstream in(std::string(MRPT_VSLAM_SOURCE_DIR) + "/CMakeLists.txt");
    ASSERT_TRUE(in.good());
    std::stringstream text;
    text << in.rdbuf();
    const std::string s = text.str();
    const std::string key = "project(mrpt_vslam VERSION ";
    const auto at = s.find(key);
    ASSERT_NE(at, std::string::npos);
    const auto begin = at + key.size();
    const auto end = s.find_first_not_of("0123456789.", begin);
    EXPECT_EQ(mrpt_vslam::core::projectVersion(), s.substr(begin, end - begin));
}

TEST(Version, MrptVersionMatchesHeaders)
{
    const std::string v = mrpt_vslam::core::mrptVersion();
    char expected[16];
    std::snprintf(expected, sizeof(expected), "%d.%d.%d", (MRPT_VERSION >> 8) & 0xF,
                  (MRPT_VERSION >> 4) & 0xF, MRPT_VERSION & 0xF);
    EXPECT_EQ(v, expected);
}

TEST(Version, VersionLineNamesTheAppAndBothVersions)
{
    EXPECT_EQ(mrpt_vslam::core::versionLine("vslam-eval"),
              "vslam-eval " + mrpt_vslam::core::projectVersion() + " (MRPT " +
                  mrpt_vslam::core::mrptVersion() + ")\n");
}
