#include <gtest/gtest.h>
#include <mrpt_vslam/core/Median.h>

#include <algorithm>
#include <random>
#include <vector>

// Against sorting, for every count from 1 to 12 (odd and even), with repeated values.
TEST(Median, MatchesSorting)
{
    std::mt19937 rng(11);
    std::uniform_int_distribution<int> u(-5, 5);
    for (size_t n = 1; n <= 12; n++)
        for (int draw = 0; draw < 20; draw++) {
            std::vector<double> v(n);
            for (double& x : v) x = 0.5 * u(rng);
            std::vector<double> s = v;
            std::sort(s.begin(), s.end());
            const double expected = n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
            EXPECT_DOUBLE_EQ(mrpt_vslam::core::median(v), expected) << n;
        }
}
