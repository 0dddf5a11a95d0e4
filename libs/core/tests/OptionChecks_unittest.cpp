#include <gtest/gtest.h>
#include <mrpt_vslam/core/OptionChecks.h>

#include <functional>
#include <stdexcept>
#include <string>

using namespace mrpt_vslam::core;

namespace {
/// what() of the std::invalid_argument `check` throws; "" when it throws none
std::string messageOf(const std::function<void()>& check)
{
    try {
        check();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(OptionChecks, ThrowOnlyWhenTheCheckFailsNamingTheKey)
{
    EXPECT_EQ(messageOf([] { requireKey(true, "S", "k", "must be > 0"); }), "");
    EXPECT_EQ(messageOf([] { requireKey(false, "S", "k", "must be > 0"); }), "[S] k: must be > 0");
    EXPECT_EQ(messageOf([] { requireOption(true, "k", "must be >= 1"); }), "");
    EXPECT_EQ(messageOf([] { requireOption(false, "k", "must be >= 1"); }), "k must be >= 1");
    EXPECT_EQ(messageOf([] { requireParameter(true, "C", "k", -1, "must be > 0"); }), "");
    EXPECT_EQ(messageOf([] { requireParameter(false, "C", "k", -1.5, "must be > 0"); }),
              "C: k = -1.5 must be > 0");
    EXPECT_EQ(messageOf([] { requireParameter(false, "C", "k", 1e9, "must be < 10"); }),
              "C: k = 1e+09 must be < 10");
}
