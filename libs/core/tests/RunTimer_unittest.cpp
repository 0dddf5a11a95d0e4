#include <gtest/gtest.h>
#include <mrpt_vslam/core/RunTimer.h>

#include <cmath>
#include <stdexcept>
#include <thread>

using mrpt_vslam::core::RunTimer;

TEST(RunTimer, NoStepsGiveZeroStatistics)
{
    const auto s = RunTimer().stepStatistics();
    EXPECT_EQ(s.count, 0u);
    EXPECT_EQ(s.total_ms, 0.0);
    EXPECT_EQ(s.mean_ms, 0.0);
    EXPECT_EQ(s.median_ms, 0.0);
    EXPECT_EQ(s.p95_ms, 0.0);
    EXPECT_EQ(s.max_ms, 0.0);
}

TEST(RunTimer, StatisticsOfOddCount)
{
    RunTimer t;
    for (double ms : {5.0, 1.0, 3.0, 2.0, 4.0}) t.addStep(ms);
    const auto s = t.stepStatistics();
    EXPECT_EQ(s.count, 5u);
    EXPECT_DOUBLE_EQ(s.total_ms, 15.0);
    EXPECT_DOUBLE_EQ(s.mean_ms, 3.0);
    EXPECT_DOUBLE_EQ(s.median_ms, 3.0);
    EXPECT_DOUBLE_EQ(s.p95_ms, 5.0);  // ceil(4.75) = 5th smallest
    EXPECT_DOUBLE_EQ(s.max_ms, 5.0);
}

TEST(RunTimer, StatisticsOfTwentyStepsUseNearestRank)
{
    RunTimer t;
    for (int i = 20; i >= 1; --i) t.addStep(i);  // 1..20 ms, added out of order
    const auto s = t.stepStatistics();
    EXPECT_EQ(s.count, 20u);
    EXPECT_DOUBLE_EQ(s.mean_ms, 10.5);
    EXPECT_DOUBLE_EQ(s.median_ms, 10.5);  // (10 + 11) / 2
    EXPECT_DOUBLE_EQ(s.p95_ms, 19.0);     // ceil(19.0) = 19th smallest
    EXPECT_DOUBLE_EQ(s.max_ms, 20.0);
    EXPECT_EQ(t.stepDurationsMs().front(), 20.0);  // kept in the order recorded
}

TEST(RunTimer, MeasuredStepIsRecorded)
{
    RunTimer t;
    t.startStep();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const double ms = t.endStep();
    EXPECT_GE(ms, 20.0);
    EXPECT_LT(ms, 5000.0);
    ASSERT_EQ(t.stepDurationsMs().size(), 1u);
    EXPECT_EQ(t.stepDurationsMs()[0], ms);
    EXPECT_GE(t.elapsedSeconds(), 0.020);
}

TEST(RunTimer, MisuseThrows)
{
    RunTimer t;
    EXPECT_THROW(t.endStep(), std::logic_error);
    EXPECT_THROW(t.addStep(-1.0), std::invalid_argument);
    EXPECT_THROW(t.addStep(std::nan("")), std::invalid_argument);
    EXPECT_EQ(t.stepStatistics().count, 0u);
}
