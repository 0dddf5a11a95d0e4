#include <gtest/gtest.h>
#include <mrpt_vslam/core/CompassSearch.h>

#include <array>
#include <cmath>
#include <limits>

using mrpt_vslam::core::compassSearch;

namespace {

/// Keeps the best point of a cost, as compassSearch()'s callers do.
template <std::size_t N, class Cost>
struct TBest {
    Cost cost;
    std::array<double, N> point{};
    double value = std::numeric_limits<double>::infinity();
    int evaluations = 0;
    bool operator()(const std::array<double, N>& p)
    {
        evaluations++;
        const double c = cost(p);
        if (!(c < value)) return false;
        value = c;
        point = p;
        return true;
    }
};

template <std::size_t N, class Cost>
TBest<N, Cost> best(Cost cost)
{
    return TBest<N, Cost>{cost};
}

}  // namespace

TEST(CompassSearch, FindsTheMinimumOfAQuadraticToTheSmallestStep)
{
    // a turned, stretched bowl: minimum at (0.3, -1.7), the closed form
    auto b = best<2>([](const std::array<double, 2>& p) {
        const double u = p[0] - 0.3, v = p[1] + 1.7;
        return 4 * u * u + 3 * u * v + v * v;
    });
    b({0, 0});
    compassSearch(b.point, {1.0, 1.0}, 1e-9, b);
    EXPECT_NEAR(b.point[0], 0.3, 1e-6);
    EXPECT_NEAR(b.point[1], -1.7, 1e-6);
}

TEST(CompassSearch, OneDimension)
{
    auto b = best<1>([](const std::array<double, 1>& t) { return std::cosh(t[0] - 2.5); });
    b({0});
    compassSearch<1>(b.point, {0.1}, 1e-12, b);
    EXPECT_NEAR(b.point[0], 2.5, 1e-5);
}

TEST(CompassSearch, MovesAtMostMaxMovesPerStepSize)
{
    // a cost that falls without end along the first axis: without the cap the search would
    // never halve its steps
    auto b = best<2>([](const std::array<double, 2>& p) { return -p[0] + p[1] * p[1]; });
    b({0, 0});
    compassSearch(b.point, {1.0, 1.0}, 1e-3, b, 10);
    // steps 1, 1/2, ..., 1/512 (the next is below 1e-3), 10 moves at each, 4 points tried per
    // move (+x moves, -x goes back, ±y rise)
    EXPECT_LE(b.evaluations, 1 + 10 * 10 * 4);
    // every move went along +x: 10 moves of each step 1, 1/2, ..., 1/512
    EXPECT_NEAR(b.point[0], 10 * (2 - 1.0 / 512), 1e-9);
    EXPECT_EQ(b.point[1], 0);
}
