// The B measurements kept per robot and step: the nearest ones, or a uniform random subset
// (checked against the enumeration of every subset), the `observation_selection` key, and the
// split of a frame's measurements by sensor.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/multirobot/CMultiRobotVisualSLAM.h>
#include <mrpt_vslam/multirobot/LandmarkMeasurement.h>

#include <algorithm>
#include <array>
#include <map>
#include <vector>

using namespace mrpt_vslam::multirobot;

namespace {
// n measurements, track_id = index, depths in a shuffled order with one tie
std::vector<TLandmarkMeasurement> measurements(size_t n)
{
    std::vector<TLandmarkMeasurement> z(n);
    for (size_t i = 0; i < n; i++) {
        z[i].track_id = static_cast<int64_t>(i);
        z[i].depth = 1.0 + static_cast<double>((i * 7) % n);
    }
    z[n - 1].depth = z[0].depth;
    return z;
}

bool isOrderedByDepth(const std::vector<TLandmarkMeasurement>& z)
{
    for (size_t i = 1; i < z.size(); i++)
        if (z[i].depth < z[i - 1].depth) return false;
    return true;
}
}  // namespace

TEST(LandmarkMeasurementSelection, NearestKeepsTheSmallestDepthsTiesInOrder)
{
    const auto z = measurements(10);
    const auto kept = selectNearest(z, 3);
    ASSERT_EQ(kept.size(), 3u);
    // brute force: a stable sort of (depth, index); i = 0 and its tie i = 9 come first
    std::vector<std::pair<double, int64_t>> sorted;
    for (const auto& m : z) sorted.emplace_back(m.depth, m.track_id);
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (size_t i = 0; i < 3; i++) EXPECT_EQ(kept[i].track_id, sorted[i].second);
    EXPECT_EQ(selectNearest(z, 0).size(), 10u);
    EXPECT_EQ(selectNearest(z, 20).size(), 10u);
}

// Every subset of 3 of 6 must come out equally often: chi-square against the 20 subsets.
TEST(LandmarkMeasurementSelection, RandomSubsetsAreUniform)
{
    const size_t n = 6, B = 3, draws = 20000;
    const auto z = measurements(n);
    mrpt::random::CRandomGenerator rng(42);
    std::map<unsigned, size_t> count;  // subset as a bit mask
    for (size_t t = 0; t < draws; t++) {
        const auto kept = selectAtRandom(z, B, rng);
        ASSERT_EQ(kept.size(), B);
        ASSERT_TRUE(isOrderedByDepth(kept));
        unsigned mask = 0;
        for (const auto& m : kept) mask |= 1u << m.track_id;
        ASSERT_EQ(__builtin_popcount(mask), static_cast<int>(B)) << "a measurement kept twice";
        count[mask]++;
    }
    size_t subsets = 0;  // brute force: every mask with B bits of n
    double chi2 = 0;
    for (unsigned mask = 0; mask < (1u << n); mask++) {
        if (__builtin_popcount(mask) != static_cast<int>(B)) continue;
        subsets++;
        const double expected = static_cast<double>(draws) / 20.0;
        const double d = static_cast<double>(count[mask]) - expected;
        chi2 += d * d / expected;
    }
    ASSERT_EQ(subsets, 20u);
    EXPECT_EQ(count.size(), 20u);
    EXPECT_LT(chi2, 43.8);  // chi2 with 19 dof, 99.9 %
}

TEST(LandmarkMeasurementSelection, RandomKeepsAllWhenBIsNotSmaller)
{
    const auto z = measurements(5);
    mrpt::random::CRandomGenerator rng(1);
    for (const size_t B : {0u, 5u, 8u}) {
        const auto kept = selectAtRandom(z, B, rng);
        ASSERT_EQ(kept.size(), 5u);
        EXPECT_TRUE(isOrderedByDepth(kept));
    }
}

// Every measurement in the list of its sensor, in the order given; sensors without any left out
TEST(LandmarkMeasurementSelection, SplitBySensorKeepsEachSensorsOrder)
{
    EXPECT_TRUE(splitBySensor({}).empty());
    auto z = measurements(9);
    const uint16_t sensors[] = {2, 0, 2, 5, 0, 2, 5, 5, 0};
    for (size_t i = 0; i < z.size(); i++) z[i].sensor = sensors[i];
    const auto bySensor = splitBySensor(z);
    ASSERT_EQ(bySensor.size(), 3u);
    size_t total = 0;
    const std::array<uint16_t, 3> present{0, 2, 5};
    for (size_t s = 0; s < bySensor.size(); s++) {
        const uint16_t sensor = bySensor[s].front().sensor;
        EXPECT_EQ(sensor, present[s]);
        std::vector<int64_t> expected;  // brute force: the track ids of that sensor, in order
        for (const auto& m : z)
            if (m.sensor == sensor) expected.push_back(m.track_id);
        std::vector<int64_t> got;
        for (const auto& m : bySensor[s]) got.push_back(m.track_id);
        EXPECT_EQ(got, expected) << "sensor " << sensor;
        total += got.size();
    }
    EXPECT_EQ(total, z.size());
}

TEST(LandmarkMeasurementSelection, IniKeyRoundTripsAndRejectsUnknownValues)
{
    CMultiRobotVisualSLAM::TOptions options;
    EXPECT_EQ(options.observation_selection, CMultiRobotVisualSLAM::TOptions::TSelection::Nearest);
    mrpt::config::CConfigFileMemory cfg;
    cfg.write("S", "observation_selection", "random");
    options.loadFromConfigFile(cfg, "S");
    EXPECT_EQ(options.observation_selection, CMultiRobotVisualSLAM::TOptions::TSelection::Random);

    mrpt::config::CConfigFileMemory saved;
    options.saveToConfigFile(saved, "S");
    CMultiRobotVisualSLAM::TOptions loaded;
    loaded.loadFromConfigFile(saved, "S");
    EXPECT_EQ(loaded.observation_selection, CMultiRobotVisualSLAM::TOptions::TSelection::Random);

    cfg.write("S", "observation_selection", "farthest");
    try {
        options.loadFromConfigFile(cfg, "S");
        FAIL() << "an unknown selection was accepted";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("observation_selection"), std::string::npos);
    }
}
