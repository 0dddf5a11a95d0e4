#include <gtest/gtest.h>
#include <mrpt_vslam/omni_fastslam/RayCrossPoint.h>

#include <cmath>

using Eigen::Vector3d;
using mrpt_vslam::omni_fastslam::angleBetweenDirections;
using mrpt_vslam::omni_fastslam::computeRayCrossPoint;

TEST(RayCrossPoint, IntersectingRaysGiveExactPoint)
{
    // Two cameras 2 m apart at 1.8 m looking at a light at (1, 3, 6.5)
    const Vector3d light(1, 3, 6.5), o1(0, 0, 1.8), o2(2, 0, 1.8);
    const Vector3d d1 = (light - o1).normalized(), d2 = (light - o2).normalized();
    const auto x = computeRayCrossPoint(o1, d1, o2, d2);
    ASSERT_FALSE(x.parallel);
    EXPECT_LT((x.point - light).norm(), 1e-12);
    EXPECT_NEAR(x.gap, 0, 1e-12);
    EXPECT_NEAR(x.s1, (light - o1).norm(), 1e-12);
    EXPECT_NEAR(x.s2, (light - o2).norm(), 1e-12);
    EXPECT_NEAR(x.angle, std::acos(d1.dot(d2)), 1e-12);
}

TEST(RayCrossPoint, SkewRaysGiveMidpointOfCommonPerpendicular)
{
    // Ray 1 along +x at z = 0; ray 2 along +y through (3, ·, 2): closest points (3,0,0), (3,0,2)
    const auto x = computeRayCrossPoint({0, 0, 0}, {1, 0, 0}, {3, -1, 2}, {0, 1, 0});
    ASSERT_FALSE(x.parallel);
    EXPECT_LT((x.point - Vector3d(3, 0, 1)).norm(), 1e-12);
    EXPECT_NEAR(x.gap, 2, 1e-12);
    EXPECT_NEAR(x.s1, 3, 1e-12);
    EXPECT_NEAR(x.s2, 1, 1e-12);
    EXPECT_NEAR(x.angle, M_PI / 2, 1e-12);
    // Non-unit directions: parameters scale inversely
    const auto y = computeRayCrossPoint({0, 0, 0}, {2, 0, 0}, {3, -1, 2}, {0, 0.5, 0});
    EXPECT_LT((y.point - Vector3d(3, 0, 1)).norm(), 1e-12);
    EXPECT_NEAR(y.s1, 1.5, 1e-12);
    EXPECT_NEAR(y.s2, 2, 1e-12);
}

TEST(RayCrossPoint, ReportsPointsBehindTheCamera)
{
    // The lines cross at (−1, 0, 0): behind camera 1 (s1 < 0), in front of camera 2
    const auto x = computeRayCrossPoint({0, 0, 0}, {1, 0, 0}, {-1, -2, 0}, {0, 1, 0});
    ASSERT_FALSE(x.parallel);
    EXPECT_LT((x.point - Vector3d(-1, 0, 0)).norm(), 1e-12);
    EXPECT_NEAR(x.s1, -1, 1e-12);
    EXPECT_NEAR(x.s2, 2, 1e-12);
}

TEST(RayCrossPoint, FlagsParallelRays)
{
    EXPECT_TRUE(computeRayCrossPoint({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 0, 1}).parallel);
    EXPECT_TRUE(computeRayCrossPoint({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 0, -3}).parallel);
    EXPECT_TRUE(computeRayCrossPoint({0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, 0, 1}).parallel);
    // Nearly parallel but above the tolerance: still solved
    EXPECT_FALSE(computeRayCrossPoint({0, 0, 0}, {0, 1e-6, 1}, {1, 0, 0}, {0, 0, 1}).parallel);
}

TEST(RayCrossPoint, AngleBetweenDirections)
{
    EXPECT_NEAR(angleBetweenDirections({1, 0, 0}, {1, 1, 0}), M_PI / 4, 1e-12);
    EXPECT_NEAR(angleBetweenDirections({1, 0, 0}, {-2, 0, 0}), M_PI, 1e-12);
    EXPECT_NEAR(angleBetweenDirections({0, 0, 1}, {0, 0, 5}), 0, 1e-12);
    // 7° (ANG_min) between two rays, precise for small angles
    const double a = 7.0 * M_PI / 180;
    EXPECT_NEAR(angleBetweenDirections({0, 0, 1}, {std::sin(a), 0, std::cos(a)}), a, 1e-14);
}
