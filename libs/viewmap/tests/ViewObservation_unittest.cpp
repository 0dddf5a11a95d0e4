#include <gtest/gtest.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/test/PlanarScene.h>
#include <mrpt_vslam/viewmap/ViewObservation.h>

#include <cmath>
#include <stdexcept>

using mrpt::math::TPose2D;
using mrpt_vslam::viewmap::predictViewObservation;
using mrpt_vslam::viewmap::viewObservationJacobians;
using mrpt_vslam::viewmap::test::angleError;

TEST(ViewObservation, KnownValues)
{
    // View ahead-left of a robot facing +x, turned by 90°.
    auto z = predictViewObservation(TPose2D(0, 0, 0), TPose2D(1, 1, M_PI / 2));
    EXPECT_NEAR(z.phi, M_PI / 4, 1e-15);
    EXPECT_NEAR(z.beta, M_PI / 2, 1e-15);
    // Robot facing +y, view straight behind it (−y): φ = −π/2 − π/2 → ±π.
    z = predictViewObservation(TPose2D(2, 3, M_PI / 2), TPose2D(2, 1, 0));
    EXPECT_NEAR(std::abs(z.phi), M_PI, 1e-12);
    EXPECT_NEAR(z.beta, -M_PI / 2, 1e-15);
    // Robot facing −x at (1, 0), view at the origin facing +x: ahead, heading difference π.
    z = predictViewObservation(TPose2D(1, 0, M_PI), TPose2D(0, 0, 0));
    EXPECT_NEAR(angleError(z.phi, 0), 0, 1e-12);
    EXPECT_NEAR(std::abs(z.beta), M_PI, 1e-12);
    // Both angles wrapped.
    z = predictViewObservation(TPose2D(0, 0, -3), TPose2D(-1, 0.1, 3));
    EXPECT_NEAR(z.beta, 6 - 2 * M_PI, 1e-12);
    EXPECT_NEAR(z.phi, std::atan2(0.1, -1) + 3 - 2 * M_PI, 1e-12);
}

// A camera ahead of the robot's centre: the bearing is between the camera centres.
TEST(ViewObservation, BearingBetweenCameraCentres)
{
    // Robot at the origin facing +x, view at (0, 2) facing +y, camera 1 m ahead: the camera
    // centres are (1, 0) and (0, 3).
    const auto z = predictViewObservation(TPose2D(0, 0, 0), TPose2D(0, 2, M_PI / 2), {1, 0});
    EXPECT_NEAR(z.phi, std::atan2(3, -1), 1e-12);
    EXPECT_NEAR(z.beta, M_PI / 2, 1e-15);
    // the same poses seen from the robots' centres
    EXPECT_NEAR(predictViewObservation(TPose2D(0, 0, 0), TPose2D(0, 2, M_PI / 2)).phi, M_PI / 2,
                1e-15);
    // a turn on the spot moves the camera: the view of a robot turned in place is no longer
    // undefined
    EXPECT_NEAR(
        angleError(predictViewObservation(TPose2D(0, 0, 0), TPose2D(0, 0, M_PI), {0.5, 0}).phi,
                   M_PI),
        0, 1e-12);
}

TEST(ViewObservation, JacobiansMatchCentralDifferences)
{
    mrpt::random::CRandomGenerator rng(8);
    const double h = 1e-6;
    for (int trial = 0; trial < 500; trial++) {
        // half of the trials with the camera off the robot's centre
        const mrpt::math::TPoint2D camera =
            trial % 2 ? mrpt::math::TPoint2D(rng.drawUniform(-0.5, 0.5), rng.drawUniform(-0.5, 0.5))
                      : mrpt::math::TPoint2D(0, 0);
        const TPose2D robot(rng.drawUniform(-5.0, 5.0), rng.drawUniform(-5.0, 5.0),
                            rng.drawUniform(-M_PI, M_PI));
        const double d = rng.drawUniform(0.2, 4.0), a = rng.drawUniform(-M_PI, M_PI);
        const TPose2D view(robot.x + d * std::cos(a), robot.y + d * std::sin(a),
                           rng.drawUniform(-M_PI, M_PI));
        const auto J = viewObservationJacobians(robot, view, camera);
        for (int i = 0; i < 3; i++) {
            for (bool wrt_robot : {true, false}) {
                TPose2D plus_v = robot, minus_v = robot, plus_l = view, minus_l = view;
                TPose2D& plus = wrt_robot ? plus_v : plus_l;
                TPose2D& minus = wrt_robot ? minus_v : minus_l;
                plus[i] += h;
                minus[i] -= h;
                const auto zp = predictViewObservation(plus_v, plus_l, camera);
                const auto zm = predictViewObservation(minus_v, minus_l, camera);
                const double dphi = angleError(zp.phi, zm.phi) / (2 * h);
                const double dbeta = angleError(zp.beta, zm.beta) / (2 * h);
                const auto& H = wrt_robot ? J.H_v : J.H_l;
                EXPECT_NEAR(H(0, i), dphi, 1e-6 * (1 + std::abs(dphi))) << trial << " " << i;
                EXPECT_NEAR(H(1, i), dbeta, 1e-6) << trial << " " << i;
            }
        }
        // The bearing depends only on the relative position: H_v + H_l = [0 0 −1; 0 0 0].
        EXPECT_NEAR((J.H_v.leftCols<2>() + J.H_l.leftCols<2>()).norm(), 0, 1e-12);
    }
}

TEST(ViewObservation, UndefinedOnTheView)
{
    const TPose2D robot(1.5, -2, 0.3);
    const TPose2D on_view(1.5, -2, 1.2);
    EXPECT_THROW(predictViewObservation(robot, on_view), std::domain_error);
    EXPECT_THROW(viewObservationJacobians(robot, on_view), std::domain_error);
    EXPECT_NO_THROW(predictViewObservation(robot, TPose2D(1.5 + 1e-9, -2, 0)));
}
