// The image front-end of the omni filter (Gamallo et al. 2013, Sec. III-A) on drawn light
// blobs: centroids and bearings back within the stated pixel noise, blobs outside the area
// limits rejected, saturated lights located by their centre.
#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/img/CImage.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/omni_fastslam/CeilingLightDetector.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

using mrpt_vslam::omni_fastslam::CeilingLightDetector;

namespace {
/// A dark 8-bit image of the camera's size.
mrpt::img::CImage darkImage(const mrpt_vslam::core::PajdlaBaksteinCamera& cam)
{
    mrpt::img::CImage img(cam.width, cam.height, mrpt::img::CH_GRAY);
    img.filledRectangle(0, 0, cam.width - 1, cam.height - 1, mrpt::img::TColor(0, 0, 0));
    return img;
}

/// Adds a round Gaussian blob centred at (u, v) [px], peak `peak` (clipped at 255: a peak
/// above 255 saturates the core), of std `sigma` [px], out to 3 σ.
void drawBlob(mrpt::img::CImage& img, double u, double v, double sigma, double peak)
{
    const int r = static_cast<int>(std::ceil(3 * sigma));
    for (int y = static_cast<int>(v) - r; y <= static_cast<int>(v) + r + 1; y++)
        for (int x = static_cast<int>(u) - r; x <= static_cast<int>(u) + r + 1; x++) {
            if (x < 0 || y < 0 || x >= int(img.getWidth()) || y >= int(img.getHeight())) continue;
            const double d2 = (x - u) * (x - u) + (y - v) * (y - v);
            if (d2 > 9 * sigma * sigma) continue;
            const double value = std::min(255.0, peak * std::exp(-0.5 * d2 / (sigma * sigma)));
            auto* p = img.ptr<uint8_t>(x, y);
            *p = static_cast<uint8_t>(std::max<double>(*p, std::round(value)));
        }
}
}  // namespace

// Lights at known (φ, θ): each blob's bearing comes back within 3 σ of its reported
// covariance, and the covariance is the stated pixel noise mapped through Eq. 1 (the error of
// a symmetric blob's centroid is far below 0.7 px, so the check is that the bound holds and is
// not loose by orders of magnitude).
TEST(CeilingLightDetector, BearingsComeBackWithinTheStatedNoise)
{
    const mrpt_vslam::core::PajdlaBaksteinCamera cam;  // the sports-hall camera
    const CeilingLightDetector detector(cam, CeilingLightDetector::TOptions());
    mrpt::obs::CObservationImage obs;
    obs.image = darkImage(cam);
    obs.cameraPose = mrpt::poses::CPose3D(0, 0, 1.8, 0, 0, 0);
    std::vector<Eigen::Vector2d> lights;  // (φ, θ)
    mrpt::random::CRandomGenerator rng(5);
    for (int i = 0; i < 12; i++) {
        const double phi = -M_PI + 2 * M_PI * (i + rng.drawUniform(0.1, 0.9)) / 12;
        const double theta = rng.drawUniform(0.2, 1.1);
        lights.emplace_back(phi, theta);
        const Eigen::Vector2d uv = cam.project(phi, theta);
        drawBlob(obs.image, uv.x(), uv.y(), 1.5, 200);
    }
    const auto bearings = detector.detect(obs, "LIGHTS");
    EXPECT_EQ(bearings->sensorLabel, "LIGHTS");
    EXPECT_NEAR(bearings->sensorLocationOnRobot.z(), 1.8, 1e-12);
    ASSERT_EQ(bearings->sensedData.size(), lights.size());
    for (const auto& m : bearings->sensedData) {
        const Eigen::Vector2d z(m.yaw, m.pitch + M_PI / 2);
        const auto nearest = std::min_element(lights.begin(), lights.end(), [&](auto& a, auto& b) {
            return (a - z).norm() < (b - z).norm();
        });
        const Eigen::Vector2d e(mrpt::math::wrapToPi(z.x() - nearest->x()), z.y() - nearest->y());
        const Eigen::Matrix2d Q = m.covariance.asEigen().block<2, 2>(1, 1);
        const double mahalanobis2 = e.dot(Q.inverse() * e);
        EXPECT_LT(mahalanobis2, 9.0) << "light at " << nearest->transpose();
        // Q is the 0.7 px centroid noise through Eq. 1: a pixel spans 0.2-0.5° here
        EXPECT_GT(std::sqrt(Q(1, 1)), 1e-4);
        EXPECT_LT(std::sqrt(Q(1, 1)), 0.02);
    }
}

// A camera wider than 180°: a blob below the horizon (θ > 90°) is not a ceiling light.
TEST(CeilingLightDetector, ReportsOnlyBlobsAboveTheHorizon)
{
    mrpt_vslam::core::PajdlaBaksteinCamera cam;
    cam.max_theta = mrpt::DEG2RAD(100.0);
    const CeilingLightDetector detector(cam, CeilingLightDetector::TOptions());
    mrpt::obs::CObservationImage obs;
    obs.image = darkImage(cam);
    for (const double theta_deg : {60.0, 95.0}) {
        const Eigen::Vector2d uv = cam.project(0.0, mrpt::DEG2RAD(theta_deg));
        drawBlob(obs.image, uv.x(), uv.y(), 1.5, 200);
    }
    ASSERT_EQ(detector.detectBlobs(obs.image).size(), 2u);
    const auto bearings = detector.detect(obs, "LIGHTS");
    ASSERT_EQ(bearings->sensedData.size(), 1u);
    EXPECT_NEAR(bearings->sensedData[0].pitch, mrpt::DEG2RAD(60.0 - 90.0), mrpt::DEG2RAD(1.0));
}

// Blobs smaller than min_blob_area (hot pixels) and larger than max_blob_area (windows,
// reflections) are not lights; a blob at the limits is.
TEST(CeilingLightDetector, RejectsBlobsOutsideTheAreaLimits)
{
    const mrpt_vslam::core::PajdlaBaksteinCamera cam;
    CeilingLightDetector::TOptions options;
    options.min_blob_area = 6;
    options.max_blob_area = 400;
    const CeilingLightDetector detector(cam, options);
    auto img = darkImage(cam);
    // a hot pixel, a 4 px speck, a 900 px window; 6 px and 400 px lights
    *img.ptr<uint8_t>(100, 100) = 255;
    img.filledRectangle(101, 300, 102, 301, mrpt::img::TColor(200, 200, 200));
    img.filledRectangle(400, 100, 429, 129, mrpt::img::TColor(255, 255, 255));
    img.filledRectangle(200, 200, 202, 201, mrpt::img::TColor(180, 180, 180));
    img.filledRectangle(300, 350, 319, 369, mrpt::img::TColor(180, 180, 180));
    const auto blobs = detector.detectBlobs(img);
    ASSERT_EQ(blobs.size(), 2u);
    std::vector<int> areas{blobs[0].area, blobs[1].area};
    std::sort(areas.begin(), areas.end());
    EXPECT_EQ(areas, (std::vector<int>{6, 400}));
    // pixels at the threshold are background
    auto dim = darkImage(cam);
    dim.filledRectangle(200, 200, 209, 209, mrpt::img::TColor(100, 100, 100));
    EXPECT_TRUE(detector.detectBlobs(dim).empty());
}

// A saturated light (a plateau of 255 over its core) is located at its centre to a tenth of a
// pixel, off the pixel grid too.
TEST(CeilingLightDetector, LocatesSaturatedLightsByTheirCentre)
{
    const mrpt_vslam::core::PajdlaBaksteinCamera cam;
    const CeilingLightDetector detector(cam, CeilingLightDetector::TOptions());
    for (const auto& [u, v] : {std::pair{250.3, 180.7}, {400.5, 300.25}, {320.0, 240.0}}) {
        auto img = darkImage(cam);
        drawBlob(img, u, v, 2.5, 900);  // 255 out to ~1.5 σ
        const auto blobs = detector.detectBlobs(img);
        ASSERT_EQ(blobs.size(), 1u);
        EXPECT_NEAR(blobs[0].u, u, 0.1);
        EXPECT_NEAR(blobs[0].v, v, 0.1);
    }
}

// A colour image (an IR image saved in colour, say) gives the blobs of its grayscale.
TEST(CeilingLightDetector, ReadsAColourImageAsItsGrayscale)
{
    const mrpt_vslam::core::PajdlaBaksteinCamera cam;
    const CeilingLightDetector detector(cam, CeilingLightDetector::TOptions());
    auto gray = darkImage(cam);
    drawBlob(gray, 250.3, 180.7, 2.0, 240);
    drawBlob(gray, 400.5, 300.2, 3.0, 200);
    const auto expected = detector.detectBlobs(gray);
    ASSERT_EQ(expected.size(), 2u);
    const auto blobs = detector.detectBlobs(gray.colorImage());
    ASSERT_EQ(blobs.size(), expected.size());
    for (size_t i = 0; i < blobs.size(); i++) {
        EXPECT_NEAR(blobs[i].u, expected[i].u, 1e-9);
        EXPECT_NEAR(blobs[i].v, expected[i].v, 1e-9);
        EXPECT_EQ(blobs[i].area, expected[i].area);
    }
}

TEST(CeilingLightDetector, RefusesImagesItCannotRead)
{
    const mrpt_vslam::core::PajdlaBaksteinCamera cam;
    const CeilingLightDetector detector(cam, CeilingLightDetector::TOptions());
    EXPECT_THROW(detector.detectBlobs(mrpt::img::CImage()), std::invalid_argument);
    mrpt::img::CImage deep;
    deep.resize(64, 48, mrpt::img::CH_GRAY, mrpt::img::PixelDepth::D16U);
    EXPECT_THROW(detector.detectBlobs(deep), std::invalid_argument);
    // an image of another size than the camera model's: its blobs would get wrong bearings
    mrpt::obs::CObservationImage obs;
    obs.image = mrpt::img::CImage(2 * cam.width, 2 * cam.height, mrpt::img::CH_GRAY);
    EXPECT_THROW(detector.detect(obs), std::invalid_argument);
    obs.image = darkImage(cam);
    EXPECT_NO_THROW(detector.detect(obs));
}
