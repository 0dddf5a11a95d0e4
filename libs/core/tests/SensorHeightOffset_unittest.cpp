#include <gtest/gtest.h>
#include <mrpt_vslam/core/SensorHeightOffset.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using mrpt_vslam::core::TSensorHeightOffset;

namespace {
/// The median by sorting (brute force).
double sortedMedian(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
}  // namespace

// The median and the MAD-based error against sorting, for odd and even counts.
TEST(SensorHeightOffset, MatchesSortedMedianAndDeviation)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (const size_t n : {2u, 3u, 10u, 11u, 101u}) {
        std::vector<double> dz(n);
        for (double& d : dz) d = u(rng);
        const auto o = TSensorHeightOffset::estimate(dz);
        const double m = sortedMedian(dz);
        std::vector<double> dev;
        for (const double d : dz) dev.push_back(std::abs(d - m));
        EXPECT_EQ(o.points, n);
        EXPECT_DOUBLE_EQ(o.dz, m) << n;
        EXPECT_NEAR(o.std_dz, 1.4826 * sortedMedian(dev) * std::sqrt(M_PI / (2.0 * n)), 1e-12) << n;
    }
}

TEST(SensorHeightOffset, FewerThanTwoPointsHaveNoError)
{
    const auto none = TSensorHeightOffset::estimate({});
    EXPECT_EQ(none.points, 0u);
    EXPECT_TRUE(std::isinf(none.std_dz));
    const auto one = TSensorHeightOffset::estimate({0.3});
    EXPECT_DOUBLE_EQ(one.dz, 0.3);
    EXPECT_TRUE(std::isinf(one.std_dz));
}

// 0.5 m offset, σ 2 cm, one point in eight paired wrongly (uniform over ±2 m): the offset
// within 1 cm; on clean normal differences the stated error is the spread of the estimates
// over many draws (within 15 %).
TEST(SensorHeightOffset, FindsOffsetDespiteWrongPairsAndStatesItsError)
{
    std::mt19937 rng(3);
    std::normal_distribution<double> n(0.5, 0.02);
    std::uniform_real_distribution<double> wrong(-2, 2);
    std::vector<double> dz;
    for (int i = 0; i < 210; i++) dz.push_back(i % 8 == 7 ? wrong(rng) : n(rng));
    const auto o = TSensorHeightOffset::estimate(dz);
    EXPECT_NEAR(o.dz, 0.5, 0.01);
    EXPECT_LT(o.std_dz, 0.004);

    double sum = 0, sum2 = 0, stated = 0;
    constexpr int kDraws = 2000;
    for (int k = 0; k < kDraws; k++) {
        std::vector<double> clean(100);
        for (double& d : clean) d = n(rng);
        const auto e = TSensorHeightOffset::estimate(clean);
        sum += e.dz;
        sum2 += e.dz * e.dz;
        stated += e.std_dz / kDraws;
    }
    const double spread = std::sqrt(sum2 / kDraws - (sum / kDraws) * (sum / kDraws));
    EXPECT_NEAR(stated / spread, 1, 0.15) << "stated " << stated << ", spread " << spread;
}
