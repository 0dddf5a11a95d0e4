// ReadingMerger against the order a whole-team rawlog gives (a sort by time, then robot), and
// its windows: a silent robot, a robot that joins late, late readings stamped after the stream.
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/team/ReadingMerger.h>

#include <algorithm>
#include <tuple>
#include <vector>

using mrpt_vslam::team::ReadingMerger;

namespace {

mrpt::Clock::time_point at(double t) { return mrpt::Clock::fromDouble(1000 + t); }

mrpt::obs::CObservation::Ptr reading(double t, const std::string& label)
{
    auto o = mrpt::obs::CObservationOdometry::Create();
    o->timestamp = at(t);
    o->sensorLabel = label;
    return o;
}

}  // namespace

// Three robots, each sending its readings in order, each at its time (wall clock = data time),
// each message delayed on the way by up to 0.9 s (under the 1 s reorder window), so that the
// robots' readings arrive interleaved at random: the merged stream is the sort by (time,
// robot) whatever the arrival, with nothing late and no window run out.
TEST(ReadingMerger, MergesInTimeOrderWhateverTheDelays)
{
    auto& rng = mrpt::random::getRandomGenerator();
    for (int trial = 0; trial < 20; trial++) {
        rng.randomize(trial + 1);
        struct TArrival {
            double wall;
            size_t robot, index;
        };
        std::vector<std::vector<double>> times(3);
        std::vector<TArrival> arrivals;
        std::vector<std::tuple<double, size_t>> expected;
        for (size_t r = 0; r < 3; r++) {
            int tenths = 0;  // many ties between the robots
            double lastArrival = 0;
            for (size_t i = 0; i < 40; i++) {
                tenths += rng.drawUniform32bit() % 3 == 0 ? 0 : rng.drawUniform32bit() % 4;
                const double t = 0.1 * tenths;
                times[r].push_back(t);
                expected.emplace_back(t, r);
                // one link per robot keeps its order
                lastArrival = std::max(lastArrival, t + rng.drawUniform(0.0, 0.9));
                arrivals.push_back({lastArrival, r, i});
            }
        }
        std::sort(expected.begin(), expected.end());
        std::stable_sort(arrivals.begin(), arrivals.end(),
                         [](const TArrival& a, const TArrival& b) { return a.wall < b.wall; });
        ReadingMerger merger({"R1", "R2", "R3"}, 1.0, 10.0);
        std::vector<std::tuple<double, size_t>> merged;
        const auto drain = [&](double now) {
            while (auto out = merger.next(now)) {
                EXPECT_FALSE(out->late);
                merged.emplace_back(mrpt::Clock::toDouble(out->observation->timestamp) - 1000,
                                    out->robot);
            }
        };
        for (const auto& a : arrivals) {
            drain(a.wall);
            const auto& t = times[a.robot];
            const auto w =
                a.index + 1 < t.size() ? at(t[a.index + 1]) : mrpt::Clock::time_point::max();
            merger.add(a.robot, reading(t[a.index], "R"), w, 0, a.wall);
            if (a.index + 1 == t.size()) merger.finish(a.robot);
        }
        drain(arrivals.back().wall);
        ASSERT_EQ(merged.size(), expected.size());
        for (size_t i = 0; i < merged.size(); i++) {
            EXPECT_NEAR(std::get<0>(merged[i]), std::get<0>(expected[i]), 1e-6) << i;
            EXPECT_EQ(std::get<1>(merged[i]), std::get<1>(expected[i])) << i;
        }
        EXPECT_TRUE(merger.done());
        EXPECT_EQ(merger.windowExpiries(), 0u);
    }
}

// R2 falls silent: R1's readings wait one reorder window, then go on without it; R2's readings
// that come back older than the stream go out at once, late, stamped just after the stream (one
// stamp per timestamp), and once R2 has caught up it holds the stream back again.
TEST(ReadingMerger, GoesOnWithoutASilentRobotAndStampsItsLateReadings)
{
    ReadingMerger merger({"R1", "R2"}, 1.0, 10.0);
    merger.add(1, reading(0, "R2"), at(0.5), 0, 0);
    merger.add(0, reading(0, "R1"), at(1), 0, 0);
    ASSERT_EQ(merger.next(0)->robot, 0u);
    ASSERT_EQ(merger.next(0)->robot, 1u);
    merger.add(0, reading(1, "R1"), at(2), 0, 0.1);
    merger.add(0, reading(2, "R1"), at(3), 0, 0.2);
    EXPECT_FALSE(merger.next(0.5));  // R2 (watermark 0.5) may still send a reading at 0.5
    EXPECT_NEAR(*merger.deadline(), 1.1, 1e-9);
    const auto first = merger.next(1.1);  // the window ran out: R2 is silent
    ASSERT_TRUE(first);
    EXPECT_EQ(first->robot, 0u);
    EXPECT_EQ(merger.windowExpiries(), 1u);
    ASSERT_TRUE(merger.next(1.1));  // no wait for R2 any more
    EXPECT_EQ(merger.streamTime(), at(2));
    // R2 comes back with readings at 0.5 (two) and 1.5: late, after the stream's time
    merger.add(1, reading(0.5, "R2"), at(0.5), 0, 2);
    merger.add(1, reading(0.5, "R2"), at(1.5), 0, 2);
    merger.add(1, reading(1.5, "R2"), at(2.5), 0, 2);
    std::vector<mrpt::Clock::time_point> stamps;
    while (auto out = merger.next(2)) {
        EXPECT_TRUE(out->late);
        EXPECT_EQ(out->robot, 1u);
        stamps.push_back(out->observation->timestamp);
    }
    ASSERT_EQ(stamps.size(), 3u);
    EXPECT_EQ(stamps[0], at(2) + ReadingMerger::kLateStep);
    EXPECT_EQ(stamps[1], stamps[0]);  // one timestamp, one stamp
    EXPECT_EQ(stamps[2], stamps[0] + ReadingMerger::kLateStep);
    // caught up (watermark 2.5 > the stream's time): R2 holds R1 back again
    merger.add(0, reading(3, "R1"), at(4), 0, 3);
    EXPECT_FALSE(merger.next(3.5));
    merger.add(1, reading(2.5, "R2"), at(5), 0, 3.6);
    const auto r2 = merger.next(3.6);
    ASSERT_TRUE(r2);
    EXPECT_EQ(r2->robot, 1u);
    EXPECT_FALSE(r2->late);
    EXPECT_EQ(merger.next(3.6)->robot, 0u);
}

// A robot never heard of holds the stream back for the join window, not the reorder window.
TEST(ReadingMerger, WaitsTheJoinWindowForARobotNotHeardYet)
{
    ReadingMerger merger({"R1", "R2"}, 1.0, 5.0);
    merger.add(0, reading(0, "R1"), at(1), 0, 0);
    EXPECT_FALSE(merger.next(2));
    EXPECT_NEAR(*merger.deadline(), 5, 1e-9);
    EXPECT_TRUE(merger.next(5));
    EXPECT_FALSE(merger.done());
    merger.finish(0);
    merger.finish(1);
    EXPECT_TRUE(merger.done());
}

// settled(t): no reading at or before t can still come on time.
TEST(ReadingMerger, IsSettledOnceEveryWatermarkHasPassed)
{
    ReadingMerger merger({"R1", "R2"}, 1.0, 10.0);
    merger.add(0, reading(1, "R1"), at(2), 0, 0);
    EXPECT_FALSE(merger.settled(at(1)));  // R1's reading waits, R2 not heard of
    merger.add(1, reading(1, "R2"), at(1.5), 0, 0);
    ASSERT_TRUE(merger.next(0));
    EXPECT_FALSE(merger.settled(at(1)));  // R2's reading at 1 still waits
    ASSERT_TRUE(merger.next(0));
    EXPECT_TRUE(merger.settled(at(1)));
    EXPECT_FALSE(merger.settled(at(1.5)));  // R2 may send a reading at 1.5
    merger.finish(1);
    EXPECT_TRUE(merger.settled(at(1.5)));
    EXPECT_FALSE(merger.settled(at(2)));  // R1 may send one at 2
}
