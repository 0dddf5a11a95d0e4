#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/FisheyeLookupTable.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

using mrpt_vslam::core::FisheyeLookupTable;
using mrpt_vslam::core::PajdlaBaksteinCamera;

namespace {

// Float storage of the angles.
constexpr double kTol = 1e-5;

const FisheyeLookupTable& defaultTable()
{
    static const FisheyeLookupTable lut{PajdlaBaksteinCamera()};
    return lut;
}

/// Radius of pixel (col, row) around the image centre, in the units of r of Eq. 1.
double pixelRadius(const PajdlaBaksteinCamera& cam, double col, double row)
{
    return std::hypot(col - cam.u0, row / cam.beta - cam.v0);
}

/** Round trip (φ, θ) → (u, v) → table. A ray that lands in a pixel lies within the pixel's range
 *  widened by at most two sampling cells (≤ 1 px with the automatic steps), converted to angles
 *  with the local rates dr/dθ (radially) and r (along the circle). Returns the errors
 *  (|Δθ|, sin θ·|Δφ|) [rad], or nothing for a point whose pixel centre lies outside the image
 *  circle (such rim pixels may be missed by the samples).
 */
std::optional<std::pair<double, double>> roundTrip(const FisheyeLookupTable& lut, double phi,
                                                   double theta)
{
    const auto& cam = lut.camera();
    const Eigen::Vector2d uv = cam.project(phi, theta);
    const auto z = lut.lookup(uv.x(), uv.y());
    if (pixelRadius(cam, std::round(uv.x()), std::round(uv.y())) > cam.radius(cam.max_theta)) {
        return std::nullopt;
    }
    EXPECT_TRUE(z.valid) << "phi=" << phi << " theta=" << theta << " uv=" << uv.transpose();
    if (!z.valid) return std::nullopt;
    const double px = 1.0 / std::min(1.0, cam.beta);  // [r units] one image pixel, at most
    const double d_theta = std::abs(theta - z.theta);
    const double d_phi = std::abs(mrpt::math::wrapToPi(phi - z.phi));
    EXPECT_LE(d_theta, z.theta_half_range + px / cam.radiusDerivative(theta) + kTol)
        << "phi=" << phi << " theta=" << theta;
    if (theta > 0) {  // φ is undefined on the axis
        EXPECT_LE(std::sin(theta) * d_phi,
                  std::sin(theta) * (z.phi_half_range + px / cam.radius(theta)) + kTol)
            << "phi=" << phi << " theta=" << theta;
    }
    // The pixel holding θ = 0 has no azimuth: leave it out of the azimuth error statistics.
    const bool holds_axis = z.theta - z.theta_half_range < kTol;
    return std::make_pair(d_theta, holds_axis ? 0.0 : std::sin(theta) * d_phi);
}

}  // namespace

TEST(FisheyeLookupTable, AutomaticStepsKeepSamplesHalfAPixelApart)
{
    const auto& lut = defaultTable();
    const auto& cam = lut.camera();
    // Closed form for the default camera: r(max_theta) and max dr/dθ on [0, max_theta] (at θ=0,
    // a/b + c/d = 160 px/rad).
    EXPECT_LE(cam.radius(cam.max_theta) * lut.deltaPhi(), 0.5 + 1e-12);
    EXPECT_LE(160.0 * lut.deltaTheta(), 0.5 + 1e-12);
    EXPECT_GT(160.0 * lut.deltaTheta(), 0.49);
    EXPECT_NEAR(std::remainder(2 * M_PI, lut.deltaPhi()), 0.0, 1e-9);
    EXPECT_NEAR(std::remainder(cam.max_theta, lut.deltaTheta()), 0.0, 1e-9);
    EXPECT_EQ(lut.memoryBytes(), 640u * 480u * sizeof(FisheyeLookupTable::TCell));
    EXPECT_EQ(sizeof(FisheyeLookupTable::TCell), 16u);
}

TEST(FisheyeLookupTable, EveryPixelInsideTheImageCircleIsHit)
{
    const auto& lut = defaultTable();
    const auto& cam = lut.camera();
    const double r_max = cam.radius(cam.max_theta);
    size_t inside = 0, outside_valid = 0;
    for (int row = 0; row < cam.height; row++) {
        for (int col = 0; col < cam.width; col++) {
            const double r = pixelRadius(cam, col, row);
            const bool valid = !std::isnan(lut.cell(col, row).phi);
            if (r <= r_max) {
                inside++;
                EXPECT_TRUE(valid) << "pixel " << col << "," << row << " r=" << r;
            } else if (r > r_max + 1.0) {
                outside_valid += valid;
            }
        }
    }
    EXPECT_EQ(outside_valid, 0u);
    EXPECT_GE(lut.validPixelCount(), inside);
    EXPECT_LE(lut.validPixelCount(), inside + static_cast<size_t>(2 * M_PI * (r_max + 1)));
}

TEST(FisheyeLookupTable, SampledRaysLieInsideTheirPixelRanges)
{
    // Every sample of the table contributed to its pixel, so its range must contain it.
    const auto& lut = defaultTable();
    const auto& cam = lut.camera();
    const int n_phi = static_cast<int>(std::lround(2 * M_PI / lut.deltaPhi()));
    const int n_theta = static_cast<int>(std::lround(cam.max_theta / lut.deltaTheta()));
    int checked = 0;
    for (int k = 0; k <= n_theta; k += 7) {
        for (int l = 0; l < n_phi; l += 11) {
            const double phi = -M_PI + l * lut.deltaPhi(), theta = k * lut.deltaTheta();
            const Eigen::Vector2d uv = cam.project(phi, theta);
            const auto z = lut.lookup(uv.x(), uv.y());
            if (!cam.isInsideImage(uv)) continue;
            ASSERT_TRUE(z.valid);
            EXPECT_LE(std::abs(theta - z.theta), z.theta_half_range + kTol);
            EXPECT_LE(std::abs(mrpt::math::wrapToPi(phi - z.phi)), z.phi_half_range + kTol);
            checked++;
        }
    }
    EXPECT_GT(checked, 15000);
}

TEST(FisheyeLookupTable, RoundTripOverTheImageCircle)
{
    const auto& lut = defaultTable();
    const auto& cam = lut.camera();
    double max_d_theta = 0, max_d_phi = 0;
    int checked = 0, rim = 0;
    const auto accumulate = [&](double phi, double theta) {
        if (!cam.isVisible(phi, theta)) return;
        const auto errors = roundTrip(lut, phi, theta);
        if (!errors) {
            rim++;
            return;
        }
        max_d_theta = std::max(max_d_theta, errors->first);
        max_d_phi = std::max(max_d_phi, errors->second);
        checked++;
    };
    for (double theta = 0; theta <= cam.max_theta; theta += mrpt::DEG2RAD(0.37)) {
        for (double phi = -M_PI; phi < M_PI; phi += mrpt::DEG2RAD(1.3)) accumulate(phi, theta);
    }
    mrpt::random::CRandomGenerator rng(42);
    for (int i = 0; i < 100000; i++) {
        accumulate(rng.drawUniform(-M_PI, M_PI), rng.drawUniform(0.0, cam.max_theta));
    }
    EXPECT_GT(checked, 120000);
    EXPECT_LT(rim, checked / 100);  // only the outermost ring of pixels
    // Resolution: a pixel spans ≈ 1 px, plus up to 1 px of sampling slack, at rates
    // dr/dθ ≥ 155 px/rad and r / sin θ ≥ 155 px/rad (measured: 0.33° and 0.28°, under 1 px).
    EXPECT_LT(max_d_theta, 1.5 / 155.0);
    EXPECT_LT(max_d_phi, 1.5 / 155.0);
    EXPECT_GT(max_d_theta, 0.5 / 160.0);  // not vacuous: errors reach about half a pixel
}

TEST(FisheyeLookupTable, WrapAroundAtPlusMinusPi)
{
    // Pixels on the −x half-axis through the centre have φ = ±π: a narrow range there, not 2π.
    const auto& lut = defaultTable();
    const auto& cam = lut.camera();
    const int row = static_cast<int>(cam.v0);
    const int r_max = static_cast<int>(cam.radius(cam.max_theta));
    for (int dc = 2; dc < r_max; dc++) {
        const auto& c = lut.cell(static_cast<int>(cam.u0) - dc, row);
        ASSERT_FALSE(std::isnan(c.phi));
        EXPECT_LE(std::abs(mrpt::math::wrapToPi(double(c.phi) - M_PI)), c.phi_half_range + kTol);
        // The pixel spans ±½ px at distance dc: atan(0.5 / (dc − 0.5)) plus sampling.
        EXPECT_LT(c.phi_half_range, std::atan(0.5 / (dc - 0.5)) + lut.deltaPhi()) << dc;
    }
    // Rays just either side of ±π round-trip to the same pixel and both lie inside its range.
    const double theta = 1.0;
    for (const double phi : {M_PI - 1e-4, -M_PI + 1e-4}) {
        const Eigen::Vector2d uv = cam.project(phi, theta);
        const auto z = lut.lookup(uv.x(), uv.y());
        ASSERT_TRUE(z.valid);
        EXPECT_LT(z.phi_half_range, 0.01);
        EXPECT_LE(std::abs(mrpt::math::wrapToPi(phi - z.phi)), z.phi_half_range + lut.deltaPhi());
    }
}

TEST(FisheyeLookupTable, CentrePixelCoversAllAzimuths)
{
    const auto& lut = defaultTable();
    const auto& cam = lut.camera();
    const auto z = lut.lookup(cam.u0, cam.v0);
    ASSERT_TRUE(z.valid);
    // θ = 0 is sampled, so the range starts at 0; φ is undefined there: the range spans 2π.
    EXPECT_NEAR(z.theta - z.theta_half_range, 0.0, kTol);
    EXPECT_LT(z.theta + z.theta_half_range, 0.5 * std::sqrt(2.0) / 150.0);
    EXPECT_GE(z.phi_half_range, M_PI - lut.deltaPhi() - kTol);
}

TEST(FisheyeLookupTable, OutsideTheImageOrCircleIsInvalid)
{
    const auto& lut = defaultTable();
    EXPECT_FALSE(lut.lookup(0, 0).valid);  // corner: radius 400 px > r(max_theta) ≈ 244 px
    EXPECT_FALSE(lut.lookup(639, 479).valid);
    EXPECT_FALSE(lut.lookup(-3, 240).valid);  // left of the image
    EXPECT_FALSE(lut.lookup(320, 480.6).valid);
    EXPECT_FALSE(lut.lookup(std::nan(""), 240).valid);
    EXPECT_TRUE(lut.lookup(320, 479.4).valid);  // bottom row, inside the circle
    EXPECT_THROW(lut.cell(640, 0), std::out_of_range);
}

TEST(FisheyeLookupTable, NonSquarePixelsAndOffCentreImage)
{
    PajdlaBaksteinCamera cam;
    cam.beta = 1.15;
    cam.u0 = 300.3;
    cam.v0 = 200.7;
    cam.max_theta = mrpt::DEG2RAD(80.0);
    const FisheyeLookupTable lut(cam);
    const double r_max = cam.radius(cam.max_theta);
    for (int row = 0; row < cam.height; row++) {
        for (int col = 0; col < cam.width; col++) {
            if (pixelRadius(cam, col, row) <= r_max) {
                ASSERT_FALSE(std::isnan(lut.cell(col, row).phi)) << col << "," << row;
            }
        }
    }
    mrpt::random::CRandomGenerator rng(7);
    int checked = 0;
    for (int i = 0; i < 20000; i++) {
        const double phi = rng.drawUniform(-M_PI, M_PI);
        const double theta = rng.drawUniform(0.0, cam.max_theta);
        if (cam.isVisible(phi, theta)) checked += roundTrip(lut, phi, theta).has_value();
    }
    EXPECT_GT(checked, 10000);
}

TEST(FisheyeLookupTable, StepsFromIniAndValidation)
{
    mrpt::config::CConfigFileMemory ini(
        "[camera]\n"
        "lut_delta_phi_deg = 0.35\n"
        "lut_delta_theta_deg = 0.3\n");
    FisheyeLookupTable::TOptions opts;
    opts.loadFromConfigFile(ini, "camera");
    EXPECT_NEAR(opts.lut_delta_phi, mrpt::DEG2RAD(0.35), 1e-12);
    EXPECT_NEAR(opts.lut_delta_theta, mrpt::DEG2RAD(0.3), 1e-12);

    const FisheyeLookupTable lut(PajdlaBaksteinCamera(), opts);
    // Steps shrink to divide the intervals: 360/0.35 → 1029 steps, 89/0.3 → 297 steps.
    EXPECT_NEAR(lut.deltaPhi(), mrpt::DEG2RAD(360.0 / 1029.0), 1e-12);
    EXPECT_NEAR(lut.deltaTheta(), mrpt::DEG2RAD(89.0 / 297.0), 1e-12);
    // Coarse steps (≈ 0.9 px apart at the rim) leave holes inside the circle: invalid pixels.
    EXPECT_LT(lut.validPixelCount(), defaultTable().validPixelCount());

    // Through text, as a saved .ini file is read back.
    mrpt::config::CConfigFileMemory saved;
    opts.saveToConfigFile(saved, "lut");
    std::string text;
    saved.getContent(text);
    FisheyeLookupTable::TOptions reread;
    reread.loadFromConfigFile(mrpt::config::CConfigFileMemory(text), "lut");
    EXPECT_NEAR(reread.lut_delta_phi, opts.lut_delta_phi, 1e-8);
    EXPECT_NEAR(reread.lut_delta_theta, opts.lut_delta_theta, 1e-8);

    mrpt::config::CConfigFileMemory bad("[camera]\nlut_delta_theta_deg = -1\n");
    EXPECT_THROW(opts.loadFromConfigFile(bad, "camera"), std::invalid_argument);
    FisheyeLookupTable::TOptions nan_opts;
    nan_opts.lut_delta_phi = std::nan("");
    EXPECT_THROW(FisheyeLookupTable(PajdlaBaksteinCamera(), nan_opts), std::invalid_argument);
}

// A model that images the field of view far beyond the image (a, c or β off by orders of
// magnitude), or steps far finer than a pixel, would take the table's build without end.
TEST(FisheyeLookupTable, RefusesMoreSamplesThanAnyImageUses)
{
    const auto samplesOf = [](const FisheyeLookupTable& lut) {
        return std::ceil(2 * M_PI / lut.deltaPhi()) *
               (std::ceil(89 * M_PI / 180 / lut.deltaTheta()) + 1);
    };
    EXPECT_LT(300 * samplesOf(defaultTable()), FisheyeLookupTable::kMaxSamples);
    PajdlaBaksteinCamera huge;
    huge.a = 1e9;
    EXPECT_THROW(FisheyeLookupTable{huge}, std::invalid_argument);
    PajdlaBaksteinCamera stretched;
    stretched.beta = 1e9;
    EXPECT_THROW(FisheyeLookupTable{stretched}, std::invalid_argument);
    FisheyeLookupTable::TOptions fine;
    fine.lut_delta_phi = fine.lut_delta_theta = 1e-7;
    EXPECT_THROW(FisheyeLookupTable(PajdlaBaksteinCamera(), fine), std::invalid_argument);
}
