#include <gtest/gtest.h>
#include <mrpt_vslam/sim/TexturedRectangle.h>

#include <algorithm>
#include <opencv2/core.hpp>

using mrpt_vslam::sim::TexturedRectangle;

namespace {

constexpr double kPpm = 100;
constexpr int kEdgeTexel = 100;  // black texels [0, 100), white from 100: edge at s = 1.0 m

TexturedRectangle stepEdge()
{
    cv::Mat mat(64, 256, CV_8UC1, cv::Scalar(255));
    mat.colRange(0, kEdgeTexel).setTo(0);
    return TexturedRectangle({0, 0, 0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 2.56,
                             0.64, mrpt::img::CImage(mat, mrpt::img::DEEP_COPY), kPpm);
}

/// s [m] where the sampled value crosses 127.5 on the row t, found by bisection.
double edgeCrossing(const TexturedRectangle& r, double footprint)
{
    double lo = 0.5, hi = 1.5;
    for (int i = 0; i < 60; i++) {
        const double mid = 0.5 * (lo + hi);
        (r.sample(mid, 0.32, footprint) < 127.5 ? lo : hi) = mid;
    }
    return lo;
}

}  // namespace

TEST(TexturedRectangle, RayIntersectionGivesTheDistanceToThePointOnTheFace)
{
    const TexturedRectangle r = stepEdge();
    EXPECT_EQ(r.normal(), Eigen::Vector3d(0, 0, -1));
    const auto hit = r.intersect({0.5, 0.25, -2}, {0.5, 0.0, 4});
    ASSERT_TRUE(hit);
    EXPECT_DOUBLE_EQ(*hit, 0.5);
    EXPECT_TRUE((r.pointAt(0.75, 0.25) - Eigen::Vector3d(0.75, 0.25, 0)).norm() < 1e-15);
    EXPECT_FALSE(r.intersect({3.0, 0.25, -2}, {0, 0, 1}));   // beside the rectangle
    EXPECT_FALSE(r.intersect({0.5, 0.25, -2}, {0, 0, -1}));  // pointing away
    EXPECT_FALSE(r.intersect({0.5, 0.25, -2}, {1, 0, 0}));   // parallel
}

TEST(TexturedRectangle, EdgesKeepTheirPositionOnEveryMipmapLevel)
{
    const TexturedRectangle r = stepEdge();
    // Footprints of 1 to 32 texels: levels 0 to 5, and between levels. A coarse level blurs the
    // step into a ramp whose linear reconstruction crosses the middle up to ~1/12 of its texel
    // away; a misaligned pyramid would be off by half a coarse texel.
    for (double footprint : {0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 8.0, 12.0, 16.0, 32.0})
        EXPECT_NEAR(edgeCrossing(r, footprint), kEdgeTexel / kPpm,
                    std::max(0.5, footprint / 10) / kPpm)
            << "footprint " << footprint;
    // Far from the edge every level gives the plain values.
    EXPECT_EQ(r.sample(0.2, 0.3, 1.0), 0.0f);
    EXPECT_EQ(r.sample(2.3, 0.3, 1.0), 255.0f);
    EXPECT_NEAR(r.sample(0.2, 0.3, 8.0), 0.0f, 1e-4);
    // A footprint of the whole texture averages it: 156 of 256 columns are white.
    EXPECT_NEAR(r.sample(1.28, 0.32, 4096.0), 255.0 * 156 / 256, 2.0);
}

TEST(TexturedRectangle, RejectsATextureThatDoesNotCoverTheFace)
{
    const mrpt::img::CImage small(10, 10, mrpt::img::CH_GRAY);
    EXPECT_THROW(TexturedRectangle({0, 0, 0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                   1.0, 1.0, small, 100),
                 std::invalid_argument);
}
