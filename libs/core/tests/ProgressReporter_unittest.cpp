#include <gtest/gtest.h>
#include <mrpt_vslam/core/ProgressReporter.h>

#include <sstream>

using mrpt_vslam::core::ProgressReporter;
using Clock = ProgressReporter::Clock;

namespace {

/** A clock the test moves by hand. */
struct FakeClock {
    Clock::time_point t{};
    void advance(double s)
    {
        t += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
    }
    ProgressReporter::TimeSource source()
    {
        return [this] { return t; };
    }
};

}  // namespace

TEST(ProgressReporter, LineShowsCountPercentRateAndEta)
{
    std::ostringstream out;
    FakeClock clock;
    ProgressReporter p("omni-fastslam", 320, false, out, clock.source());
    EXPECT_EQ(p.formatLine(120, 1.5, false),
              "[omni-fastslam] frame 120/320 (37%)  80.0 frames/s  ETA 2.5 s");
    EXPECT_EQ(p.formatLine(0, 0.0, false), "[omni-fastslam] frame 0/320 (0%)");
    EXPECT_EQ(p.formatLine(10, 10.0, false),
              "[omni-fastslam] frame 10/320 (3%)  1.0 frames/s  ETA 5 min 10 s");
    EXPECT_EQ(p.formatLine(1, 10.0, false),
              "[omni-fastslam] frame 1/320 (0%)  0.1 frames/s  ETA 53 min 10 s");
    EXPECT_EQ(p.formatLine(1, 100.0, false),  // 31900 s
              "[omni-fastslam] frame 1/320 (0%)  0.0 frames/s  ETA 8 h 52 min");
    EXPECT_EQ(out.str(), "");  // formatting draws nothing
}

TEST(ProgressReporter, UnknownTotalHasNoEta)
{
    std::ostringstream out;
    FakeClock clock;
    ProgressReporter p("view-slam", 0, false, out, clock.source(), "step");
    EXPECT_EQ(p.formatLine(50, 2.0, false), "[view-slam] step 50  25.0 steps/s");
}

TEST(ProgressReporter, RedrawsInPlaceAtMostFourTimesPerSecond)
{
    std::ostringstream out;
    FakeClock clock;
    ProgressReporter p("app", 100, false, out, clock.source());
    clock.advance(1.0);
    p.update(10);  // first call draws
    clock.advance(0.1);
    p.update(11);  // too soon
    clock.advance(0.1);
    p.update(12);  // 0.2 s since last draw: still too soon
    clock.advance(0.05);
    p.update(13);  // 0.25 s: draws
    clock.advance(0.75);
    p.finish(100);
    EXPECT_EQ(out.str(),
              "\r[app] frame 10/100 (10%)  10.0 frames/s  ETA 9.0 s"
              "\r[app] frame 13/100 (13%)  10.4 frames/s  ETA 8.4 s"
              "\r[app] frame 100/100 (100%)  50.0 frames/s  done in 2.0 s\n");
}

TEST(ProgressReporter, ShorterLineBlanksTheRestOfTheLongerOne)
{
    std::ostringstream out;
    FakeClock clock;
    ProgressReporter p("a", 0, false, out, clock.source(), "frame", 0.0);
    clock.advance(1.0);
    p.update(1000);  // "[a] frame 1000  1000.0 frames/s" (31 chars)
    p.update(9);     // "[a] frame 9  9.0 frames/s" (25 chars) + 6 blanks
    EXPECT_EQ(out.str(),
              "\r[a] frame 1000  1000.0 frames/s"
              "\r[a] frame 9  9.0 frames/s      ");
}

TEST(ProgressReporter, QuietWritesNothing)
{
    std::ostringstream out;
    FakeClock clock;
    {
        ProgressReporter p("app", 10, true, out, clock.source());
        clock.advance(1.0);
        p.update(5);
        p.finish(10);
    }
    EXPECT_EQ(out.str(), "");
}

TEST(ProgressReporter, UnfinishedLineIsEndedOnDestruction)
{
    std::ostringstream out;
    FakeClock clock;
    {
        ProgressReporter p("app", 0, false, out, clock.source());
        p.update(3);
    }
    EXPECT_EQ(out.str(), "\r[app] frame 3\n");
}

TEST(ProgressReporter, FinishIsFinal)
{
    std::ostringstream out;
    FakeClock clock;
    ProgressReporter p("app", 4, false, out, clock.source());
    clock.advance(2.0);
    p.finish(4);
    p.update(5);
    p.finish(5);
    EXPECT_EQ(out.str(), "\r[app] frame 4/4 (100%)  2.0 frames/s  done in 2.0 s\n");
}
