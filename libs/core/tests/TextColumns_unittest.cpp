#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt_vslam/core/TextColumns.h>
#include <mrpt_vslam/core/UsageError.h>

#include <stdexcept>
#include <string>
#include <vector>

using mrpt_vslam::core::parseNumbers;
using mrpt_vslam::core::readNumberList;
using mrpt_vslam::core::UsageError;

namespace {

std::string errorOf(const std::string& value)
{
    const mrpt::config::CConfigFileMemory cfg("[S]\nk = " + value + "\n");
    try {
        readNumberList(cfg, "S", "k", {});
    } catch (const UsageError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(TextColumns, ParsesNumbersAndNamesTheBadToken)
{
    EXPECT_EQ(parseNumbers(" 1 -2.5\t3e2 ", "f:1: "), (std::vector<double>{1, -2.5, 300}));
    EXPECT_TRUE(parseNumbers("", "f:1: ").empty());
    EXPECT_THROW(parseNumbers("1 2x", "f:1: "), std::runtime_error);
    try {
        parseNumbers("1 inf", "f:7: ");
        FAIL() << "inf was accepted";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "f:7: non-finite value");
    }
}

TEST(TextColumns, ReadsAConfigListSeparatedByCommasOrBlanks)
{
    const mrpt::config::CConfigFileMemory cfg("[S]\na = 1, 2,3 4\nempty =\n");
    EXPECT_EQ(readNumberList(cfg, "S", "a", {}), (std::vector<double>{1, 2, 3, 4}));
    EXPECT_TRUE(readNumberList(cfg, "S", "empty", {9}).empty());
    EXPECT_EQ(readNumberList(cfg, "S", "absent", {9}), std::vector<double>{9});

    EXPECT_EQ(errorOf("1, abc, 0"), "[S] k: 'abc' is not a number");
    EXPECT_EQ(errorOf("1 nan 0"), "[S] k: non-finite value");
}
