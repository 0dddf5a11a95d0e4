#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/img/TCamera.h>
#include <mrpt_vslam/core/PajdlaBaksteinFit.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

using mrpt_vslam::core::fitPajdlaBakstein;
using mrpt_vslam::core::TPajdlaBaksteinFit;

namespace {

mrpt::img::TCamera calibration(int width, int height, double fx, double fy, double cx, double cy)
{
    mrpt::img::TCamera camera;
    camera.ncols = static_cast<uint32_t>(width);
    camera.nrows = static_cast<uint32_t>(height);
    camera.setIntrinsicParamsFromValues(fx, fy, cx, cy);
    return camera;
}

/// The pixel of a point in the camera frame as OpenCV's projectPoints and fisheye::projectPoints
/// compute it (normalized point, then distortion), written out for the test.
Eigen::Vector2d pixelOf(const mrpt::img::TCamera& cam, double x, double y, double z)
{
    const double xn = x / z, yn = y / z, rn = std::hypot(xn, yn);
    double scale = 1;  // distorted / undistorted normalized radius
    if (cam.distortion == mrpt::img::DistortionModel::kannala_brandt) {
        const double th = std::atan(rn);
        const double thd = th * (1 + cam.k1() * std::pow(th, 2) + cam.k2() * std::pow(th, 4) +
                                 cam.k3() * std::pow(th, 6) + cam.k4() * std::pow(th, 8));
        scale = rn > 0 ? thd / rn : 1;
    } else if (cam.distortion == mrpt::img::DistortionModel::plumb_bob) {
        const double r2 = rn * rn;
        scale = 1 + cam.k1() * r2 + cam.k2() * r2 * r2 + cam.k3() * r2 * r2 * r2;
    }
    return {cam.cx() + cam.fx() * scale * xn, cam.cy() + cam.fy() * scale * yn};
}

/// Largest pixel distance between the fit and the calibration over random rays of its field of
/// view (θ < 90°: in front of the camera, where pixelOf() is defined).
double largestPixelError(const TPajdlaBaksteinFit& fit, const mrpt::img::TCamera& cam)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0, 1);
    double largest = 0;
    for (int i = 0; i < 20000; i++) {
        const double phi = (2 * unit(rng) - 1) * M_PI;
        const double theta = unit(rng) * std::min(fit.camera.max_theta, 1.5);
        const double x = std::sin(theta) * std::cos(phi), y = std::sin(theta) * std::sin(phi);
        largest = std::max(
            largest, (fit.camera.project(phi, theta) - pixelOf(cam, x, y, std::cos(theta))).norm());
    }
    return largest;
}

}  // namespace

// A pinhole is the model with b = 1, c = 0: the fit is exact; its field of view ends at the
// farthest image corner, atan(400.72 / 300) = 53.18°.
TEST(PajdlaBaksteinFit, PinholeIsExact)
{
    const auto cam = calibration(640, 480, 300, 300, 320, 240);
    const auto fit = fitPajdlaBakstein(cam, mrpt::DEG2RAD(89.0));
    EXPECT_LT(fit.max_error_px, 0.01);
    EXPECT_NEAR(mrpt::RAD2DEG(fit.camera.max_theta), 53.18, 0.06);
    EXPECT_LT(largestPixelError(fit, cam), 0.01);
    EXPECT_EQ(fit.camera.width, 640);
    EXPECT_EQ(fit.camera.height, 480);
}

// Kannala-Brandt fisheyes. An equidistant lens (k = 0, r = f θ) is within a hundredth of a
// pixel to 89°. The distortion of a calibrated 848 × 800 fisheye with non-square pixels has a
// wiggle that the model's two shape parameters follow less well: measured 0.93 px (0.22°) up to
// 70°, 2.0 px (0.53°) up to 89°. Either way the error it reports is
// the largest found by projecting random rays through both.
TEST(PajdlaBaksteinFit, KannalaBrandt)
{
    auto equidistant = calibration(640, 480, 150, 150, 320, 240);
    equidistant.setDistortionKannalaBrandt(0, 0, 0, 0);
    auto lens = calibration(848, 800, 284.9, 286.2, 425.9, 398.1);
    lens.setDistortionKannalaBrandt(-0.0073, 0.0430, -0.0409, 0.0076);
    struct TCase {
        const mrpt::img::TCamera& camera;
        double max_theta_deg, bound_px, bound_deg;
    };
    for (const TCase& c : {TCase{equidistant, 89, 0.01, 0.01}, TCase{lens, 70, 1.0, 0.25},
                           TCase{lens, 89, 2.5, 0.6}}) {
        const auto fit = fitPajdlaBakstein(c.camera, mrpt::DEG2RAD(c.max_theta_deg));
        std::printf(
            "fx %.1f, up to %.0f deg: a %.6g b %.6g c %.6g d %.6g, max error %.3f px "
            "(%.3f deg)\n",
            c.camera.fx(), c.max_theta_deg, fit.camera.a, fit.camera.b, fit.camera.c, fit.camera.d,
            fit.max_error_px, fit.max_error_deg);
        EXPECT_NEAR(fit.camera.max_theta, mrpt::DEG2RAD(c.max_theta_deg), 1e-12)
            << "inside the image";
        EXPECT_LT(fit.max_error_px, c.bound_px);
        EXPECT_LT(fit.max_error_deg, c.bound_deg);
        const double found = largestPixelError(fit, c.camera);
        EXPECT_LE(found, fit.max_error_px * std::max(1.0, fit.camera.beta) + 1e-9);
        EXPECT_GT(found, 0.5 * fit.max_error_px);
        EXPECT_NEAR(fit.camera.beta, c.camera.fy() / c.camera.fx(), 1e-12);
        EXPECT_NEAR(fit.camera.u0, c.camera.cx(), 1e-12);
        EXPECT_NEAR(fit.camera.beta * fit.camera.v0, c.camera.cy(), 1e-9);
    }
}

// Radial plumb_bob distortion (barrel, k1 = -0.3, k2 = 0.1): the field of view ends at the
// farthest image corner; measured 1.35 px at most.
TEST(PajdlaBaksteinFit, RadialPlumbBob)
{
    auto cam = calibration(640, 480, 400, 400, 330, 235);
    cam.setDistortionPlumbBob(-0.3, 0.1, 0, 0, 0);
    const auto fit = fitPajdlaBakstein(cam, mrpt::DEG2RAD(89.0));
    EXPECT_LT(fit.max_error_px, 1.5);
    EXPECT_LE(largestPixelError(fit, cam), fit.max_error_px + 1e-9);
    const Eigen::Vector2d corner(-0.5, 479.5);  // the farthest from (330, 235)
    const double edge = cam.fx() * mrpt_vslam::core::calibrationRadius(cam, fit.camera.max_theta);
    EXPECT_LE(edge, (corner - Eigen::Vector2d(330, 235)).norm());
    EXPECT_GT(edge, (corner - Eigen::Vector2d(330, 235)).norm() - 1);
}

TEST(PajdlaBaksteinFit, RefusesWhatNoRadialModelHolds)
{
    auto noFocal = calibration(640, 480, 0, 0, 320, 240);
    EXPECT_THROW(fitPajdlaBakstein(noFocal, 1.5), std::invalid_argument);
    auto noSize = calibration(0, 0, 300, 300, 320, 240);
    EXPECT_THROW(fitPajdlaBakstein(noSize, 1.5), std::invalid_argument);
    auto tangential = calibration(640, 480, 300, 300, 320, 240);
    tangential.setDistortionPlumbBob(0, 0, 0.01, 0, 0);
    EXPECT_THROW(fitPajdlaBakstein(tangential, 1.5), std::invalid_argument);
    auto folding = calibration(640, 480, 300, 300, 320, 240);
    folding.setDistortionKannalaBrandt(-50, 0, 0, 0);  // ρ' = 1 - 150 θ² < 0 from 4.7°
    EXPECT_THROW(fitPajdlaBakstein(folding, 1.5), std::invalid_argument);
}
