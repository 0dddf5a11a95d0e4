// The project's camera models fitted to MRPT camera calibrations (core::RadialCalibration):
// fitPajdlaBakstein() and fitUnifiedSphere(), each reported error checked against rays
// projected through the fit and through the calibration.
#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/img/TCamera.h>
#include <mrpt_vslam/core/PajdlaBaksteinFit.h>
#include <mrpt_vslam/core/UnifiedSphereFit.h>
#include <mrpt_vslam/test/CalibratedImages.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>

using mrpt_vslam::core::fitPajdlaBakstein;
using mrpt_vslam::core::fitUnifiedSphere;
using mrpt_vslam::core::RadialCalibration;

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

/// Largest pixel distance between a fitted model, `project(φ, θ)`, and the calibration over
/// random rays up to `max_theta` (and θ < 90°: in front of the camera, where pixelOf() is
/// defined) that the model projects into the image.
double largestPixelError(
    double max_theta, const mrpt::img::TCamera& cam,
    const std::function<std::optional<Eigen::Vector2d>(double, double)>& project)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0, 1);
    double largest = 0;
    for (int i = 0; i < 20000; i++) {
        const double phi = (2 * unit(rng) - 1) * M_PI;
        const double theta = unit(rng) * std::min(max_theta, 1.5);
        const double x = std::sin(theta) * std::cos(phi), y = std::sin(theta) * std::sin(phi);
        const auto uv = project(phi, theta);
        if (uv) largest = std::max(largest, (*uv - pixelOf(cam, x, y, std::cos(theta))).norm());
    }
    return largest;
}

double largestPixelError(const mrpt_vslam::core::TPajdlaBaksteinFit& fit,
                         const mrpt::img::TCamera& cam)
{
    return largestPixelError(fit.camera.max_theta, cam, [&fit](double phi, double theta) {
        return std::optional<Eigen::Vector2d>(fit.camera.project(phi, theta));
    });
}

double largestPixelError(const mrpt_vslam::core::TUnifiedSphereFit& fit,
                         const mrpt::img::TCamera& cam)
{
    return largestPixelError(fit.camera.max_theta, cam, [&fit](double phi, double theta) {
        return fit.camera.project(
            {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
    });
}

/// An equidistant fisheye (Kannala-Brandt, k = 0: r = f θ), f = 150 px, 640 × 480.
mrpt::img::TCamera equidistantFisheye()
{
    auto cam = calibration(640, 480, 150, 150, 320, 240);
    cam.setDistortionKannalaBrandt(0, 0, 0, 0);
    return cam;
}

/// The Kannala-Brandt calibration of a real 848 × 800 fisheye with non-square pixels.
mrpt::img::TCamera calibratedFisheye()
{
    auto cam = calibration(848, 800, 284.9, 286.2, 425.9, 398.1);
    cam.setDistortionKannalaBrandt(-0.0073, 0.0430, -0.0409, 0.0076);
    return cam;
}

/// A calibration, the field of view asked of a fit, and the bounds on its errors.
struct TFisheyeCase {
    mrpt::img::TCamera camera;
    double max_theta_deg, bound_px, bound_deg;
};

/** The checks of a fit to a fisheye case: the field of view asked (the image holds it), errors
 *  within the bounds, and the error reported the largest found by projecting random rays
 *  (up to the aspect fy / fx, which scales the rows, and a thousandth: the fit's own error is
 *  taken at 4001 angles). */
template <class Fit>
void expectFitWithinBounds(const Fit& fit, const TFisheyeCase& c)
{
    EXPECT_NEAR(fit.camera.max_theta, mrpt::DEG2RAD(c.max_theta_deg), 1e-12) << "inside the image";
    EXPECT_LT(fit.max_error_px, c.bound_px);
    EXPECT_LT(fit.max_error_deg, c.bound_deg);
    const double found = largestPixelError(fit, c.camera);
    EXPECT_LE(found,
              fit.max_error_px * std::max(1.0, c.camera.fy() / c.camera.fx()) * 1.001 + 1e-9);
    EXPECT_GT(found, 0.5 * fit.max_error_px);
}

/// The message of the std::invalid_argument by which `fit()` refuses; a failure if it fits.
template <class Fit>
std::string refusal(const Fit& fit)
{
    try {
        (void)fit();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    ADD_FAILURE() << "fitted";
    return {};
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
    for (const TFisheyeCase& c : {TFisheyeCase{equidistantFisheye(), 89, 0.01, 0.01},
                                  TFisheyeCase{calibratedFisheye(), 70, 1.0, 0.25},
                                  TFisheyeCase{calibratedFisheye(), 89, 2.5, 0.6}}) {
        const auto fit = fitPajdlaBakstein(c.camera, mrpt::DEG2RAD(c.max_theta_deg));
        std::printf(
            "fx %.1f, up to %.0f deg: a %.6g b %.6g c %.6g d %.6g, max error %.3f px "
            "(%.3f deg)\n",
            c.camera.fx(), c.max_theta_deg, fit.camera.a, fit.camera.b, fit.camera.c, fit.camera.d,
            fit.max_error_px, fit.max_error_deg);
        expectFitWithinBounds(fit, c);
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
    const double edge = RadialCalibration(cam).radius(fit.camera.max_theta);
    EXPECT_LE(edge, (corner - Eigen::Vector2d(330, 235)).norm());
    EXPECT_GT(edge, (corner - Eigen::Vector2d(330, 235)).norm() - 1);
}

// A pinhole is the model with ξ = 0: the fit is exact.
TEST(UnifiedSphereFit, PinholeIsExact)
{
    const auto cam = calibration(640, 480, 300, 300, 320, 240);
    const auto fit = fitUnifiedSphere(cam, mrpt::DEG2RAD(89.0));
    EXPECT_LT(fit.camera.xi, 1e-4);
    EXPECT_NEAR(fit.camera.fx, 300, 0.01);
    EXPECT_LT(fit.max_error_px, 0.01);
    EXPECT_LT(largestPixelError(fit, cam), 0.01);
    EXPECT_NEAR(mrpt::RAD2DEG(fit.camera.max_theta), 53.18, 0.06);
}

// The Kannala-Brandt calibration of a catadioptric camera (ξ = 0.8, γ = 150 px, 640 × 480,
// calibrated up to 100° from the axis) gives that camera back: measured ξ 0.8003, γ 150.06 px,
// within 0.03 px (0.014°), the Kannala-Brandt polynomial's own error.
TEST(UnifiedSphereFit, KannalaBrandtOfACatadioptricCamera)
{
    const auto cam = mrpt_vslam::test::kannalaBrandtCalibration(
        [](double theta) {
            return 150 * mrpt_vslam::core::UnifiedSphereCamera::normalizedRadius(theta, 0.8);
        },
        mrpt::DEG2RAD(100.0), 640, 480, 319.5, 239.5);
    const auto fit = fitUnifiedSphere(cam, mrpt::DEG2RAD(100.0));
    std::printf("xi %.6f fx %.4f fy %.4f, max error %.4f px (%.4f deg)\n", fit.camera.xi,
                fit.camera.fx, fit.camera.fy, fit.max_error_px, fit.max_error_deg);
    EXPECT_NEAR(fit.camera.xi, 0.8, 0.002);
    EXPECT_NEAR(fit.camera.fx, 150, 0.2);
    EXPECT_EQ(fit.camera.fy, fit.camera.fx);
    EXPECT_NEAR(mrpt::RAD2DEG(fit.camera.max_theta), 100, 1e-9);
    EXPECT_LT(fit.max_error_px, 0.05);
    EXPECT_LT(fit.max_error_deg, 0.02);
    EXPECT_LE(largestPixelError(fit, cam), fit.max_error_px * 1.001);
    EXPECT_NEAR(fit.camera.cx, 319.5, 1e-12);
    EXPECT_NEAR(fit.camera.cy, 239.5, 1e-12);
}

// Fisheyes: the equidistant lens and the calibrated 848 × 800 fisheye. The model has one shape
// parameter: measured 0.62 px (0.24°) up to 89° for the first; 0.95 px (0.21°) up to 70° and 3.4 px
// (1.13°) up to 89° for the second, about the Pajdla-Bakstein fit's to 70° and not as close beyond.
TEST(UnifiedSphereFit, KannalaBrandt)
{
    for (const TFisheyeCase& c : {TFisheyeCase{equidistantFisheye(), 89, 0.7, 0.3},
                                  TFisheyeCase{calibratedFisheye(), 70, 1.0, 0.25},
                                  TFisheyeCase{calibratedFisheye(), 89, 3.6, 1.2}}) {
        const auto fit = fitUnifiedSphere(c.camera, mrpt::DEG2RAD(c.max_theta_deg));
        std::printf("fx %.1f, up to %.0f deg: xi %.6g fx %.6g, max error %.3f px (%.3f deg)\n",
                    c.camera.fx(), c.max_theta_deg, fit.camera.xi, fit.camera.fx, fit.max_error_px,
                    fit.max_error_deg);
        expectFitWithinBounds(fit, c);
        EXPECT_NEAR(fit.camera.fy / fit.camera.fx, c.camera.fy() / c.camera.fx(), 1e-12);
        EXPECT_NEAR(fit.camera.cx, c.camera.cx(), 1e-12);
        EXPECT_NEAR(fit.camera.cy, c.camera.cy(), 1e-12);
    }
}

// Both fits refuse, naming the problem, what no radial model holds.
TEST(CameraFit, RefusesWhatNoRadialModelHolds)
{
    auto noFocal = calibration(640, 480, 0, 0, 320, 240);
    auto noSize = calibration(0, 0, 300, 300, 320, 240);
    auto tangential = calibration(640, 480, 300, 300, 320, 240);
    tangential.setDistortionPlumbBob(0, 0, 0.01, 0, 0);
    auto folding = calibration(640, 480, 300, 300, 320, 240);
    folding.setDistortionKannalaBrandt(-50, 0, 0, 0);  // ρ' = 1 - 150 θ² < 0 from 4.7°
    for (const auto& cam : {noFocal, noSize, tangential, folding}) {
        EXPECT_THROW(fitPajdlaBakstein(cam, 1.5), std::invalid_argument);
        EXPECT_THROW(fitUnifiedSphere(cam, 1.5), std::invalid_argument);
    }
}

// A barrel pinhole whose radius flattens at the edge of its field of view (k1 = -0.2: ρ stops
// increasing at 52.2°): the unified sphere model fits it up to there; the Pajdla-Bakstein fit
// would turn down just before, so its field of view is narrowed to where it still increases,
// and its reported error holds there.
TEST(CameraFit, NarrowsTheFieldOfViewWhereTheModelWouldTurnDown)
{
    auto barrel = calibration(640, 480, 300, 300, 319.5, 239.5);
    barrel.setDistortionPlumbBob(-0.2, 0, 0, 0, 0);
    const auto sphere = fitUnifiedSphere(barrel, 1.5);
    EXPECT_LT(sphere.max_error_px, 6);
    const auto fisheye = fitPajdlaBakstein(barrel, 1.5);
    const double edge = sphere.camera.max_theta;
    EXPECT_NEAR(mrpt::RAD2DEG(edge), 52.2, 0.1);
    EXPECT_LT(fisheye.camera.max_theta, edge);
    EXPECT_GT(fisheye.camera.max_theta, 0.9 * edge);
    EXPECT_EQ(fisheye.camera.increasingUpTo(fisheye.camera.max_theta), fisheye.camera.max_theta);
    // measured: up to 51.2 deg, within 2.14 px (1.19 deg: the radius is nearly flat there);
    // the unified sphere model 5.5 px
    EXPECT_LT(fisheye.max_error_px, 2.5);
    const double found = largestPixelError(fisheye, barrel);
    EXPECT_LE(found, fisheye.max_error_px * 1.001 + 1e-9);
    EXPECT_GT(found, 0.5 * fisheye.max_error_px);
}

// A barrel whose polynomial steepens towards the image's corners (k1 = -0.3, k2 = 0.1 at
// f = 300 px: the slope at 57° is twice that of any unified sphere model) is refused by that
// fit, naming the angle; up to 50° it is fitted (measured 2.88 px at most).
TEST(CameraFit, RefusesACalibrationNoModelFollowsSteeplyEnough)
{
    auto barrel = calibration(640, 480, 300, 300, 319.5, 239.5);
    barrel.setDistortionPlumbBob(-0.3, 0.1, 0, 0, 0);
    EXPECT_EQ(refusal([&] { return fitUnifiedSphere(barrel, 1.5); }),
              "no unified sphere model has half the slope of the calibration's radius "
              "everywhere up to 57.2 deg from the axis");
    EXPECT_LT(fitUnifiedSphere(barrel, mrpt::DEG2RAD(50.0)).max_error_px, 3);
}
