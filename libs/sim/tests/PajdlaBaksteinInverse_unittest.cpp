#include <gtest/gtest.h>
#include <mrpt_vslam/sim/PajdlaBaksteinInverse.h>

#include <cmath>

using mrpt_vslam::core::PajdlaBaksteinCamera;
using mrpt_vslam::sim::PajdlaBaksteinInverse;

TEST(PajdlaBaksteinInverse, InvertsEquation1)
{
    PajdlaBaksteinCamera cam;
    cam.beta = 1.05;
    const PajdlaBaksteinInverse inv(cam);
    double worst = 0;
    for (double theta = 0.01; theta < cam.max_theta; theta += 0.037) {
        for (double phi = -3.1; phi < 3.14; phi += 0.11) {
            const Eigen::Vector2d a = inv.unproject(cam.project(phi, theta));
            worst = std::max({worst, std::abs(a.y() - theta),
                              std::abs(std::remainder(a.x() - phi, 2 * M_PI)) * std::sin(theta)});
        }
    }
    EXPECT_LT(worst, 1e-9);
}

TEST(PajdlaBaksteinInverse, RayOfTheImageCentreIsTheOpticalAxis)
{
    const PajdlaBaksteinCamera cam;
    const PajdlaBaksteinInverse inv(cam);
    const Eigen::Vector3d d = inv.rayOfPixel({cam.u0, cam.v0});
    EXPECT_NEAR(d.z(), 1.0, 1e-12);
    EXPECT_DOUBLE_EQ(inv.thetaOfRadius(0), 0.0);
}
