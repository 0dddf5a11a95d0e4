#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <mrpt_vslam/sim/OmniRenderer.h>

#include <cmath>
#include <iostream>
#include <opencv2/core.hpp>

using namespace mrpt_vslam::sim;

namespace {

constexpr double kPpm = 20;  // [texel/m] of the test planes

/// The camera of the shipped omni-views scenario (640 × 480, ξ = 0.9, f = 172 px, 200°).
mrpt_vslam::core::UnifiedSphereCamera testCamera()
{
    mrpt_vslam::core::UnifiedSphereCamera c;
    c.xi = 0.9;
    c.fx = c.fy = 172;
    c.cx = 319.5;
    c.cy = 239.5;
    c.width = 640;
    c.height = 480;
    c.max_theta = mrpt::DEG2RAD(100.0);
    return c;
}

/// Smooth texture of `cols` × `rows` texels (periods of 38 and 57 texels).
cv::Mat smoothTexture(int cols, int rows)
{
    cv::Mat m(rows, cols, CV_8UC1);
    for (int r = 0; r < rows; r++)
        for (int c = 0; c < cols; c++)
            m.at<uint8_t>(r, c) =
                cv::saturate_cast<uint8_t>(128 + 90 * std::sin(c / 6.0) * std::cos(r / 9.0));
    return m;
}

/// Bilinear value of `m` at (x, y) [texels, centres at integers], as the test's own reference.
double bilinear(const cv::Mat& m, double x, double y)
{
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    const auto at = [&](int c, int r) { return static_cast<double>(m.at<uint8_t>(r, c)); };
    return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
           fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

/// Bilinear value of a rendered radiance at pixel (u, v).
double bilinear(const TRenderedView& v, const Eigen::Vector2d& uv)
{
    const int u0 = static_cast<int>(std::floor(uv.x())), v0 = static_cast<int>(std::floor(uv.y()));
    const double fx = uv.x() - u0, fy = uv.y() - v0;
    const auto at = [&](int c, int r) {
        return static_cast<double>(v.radiance[static_cast<size_t>(r) * v.width + c]);
    };
    return (1 - fy) * ((1 - fx) * at(u0, v0) + fx * at(u0 + 1, v0)) +
           fy * ((1 - fx) * at(u0, v0 + 1) + fx * at(u0 + 1, v0 + 1));
}

/** A 10 × 10 m horizontal plane at height z (texture s along world x, t along world y, from
 *  (−5, −5)) with `texture`. */
TexturedRectangle ceilingPlane(double z, const cv::Mat& texture)
{
    return TexturedRectangle(Eigen::Vector3d(-5, -5, z), Eigen::Vector3d::UnitX(),
                             Eigen::Vector3d::UnitY(), 10, 10,
                             mrpt::img::CImage(texture, mrpt::img::DEEP_COPY), kPpm);
}

/// An upward camera (z up) moved and turned about the vertical.
const mrpt::poses::CPose3D kCameraPose(0.3, -0.2, 0.1, mrpt::DEG2RAD(30.0), 0, 0);

}  // namespace

TEST(OmniRenderer, PixelsShowTheTextureWhereTheModelProjectsThePlane)
{
    const cv::Mat texture = smoothTexture(200, 200);
    TexturedScene scene;
    scene.rectangles.push_back(ceilingPlane(1.2, texture));
    OmniRenderer renderer;
    renderer.setCamera(testCamera());
    const TRenderedView view = renderer.renderView(scene, kCameraPose);
    const auto& cam = renderer.camera();

    // (a) Points of the plane: texture there vs the rendered image at the model's projection.
    double max_error_a = 0;
    int points = 0;
    for (double x = -1.5; x <= 2.0; x += 0.23) {
        for (double y = -1.9; y <= 1.6; y += 0.31) {
            const mrpt::math::TPoint3D p =
                kCameraPose.inverseComposePoint(mrpt::math::TPoint3D(x, y, 1.2));
            const auto uv = cam.project(Eigen::Vector3d(p.x, p.y, p.z));
            ASSERT_TRUE(uv) << x << " " << y;
            const double expected = bilinear(texture, (x + 5) * kPpm - 0.5, (y + 5) * kPpm - 0.5);
            max_error_a = std::max(max_error_a, std::abs(bilinear(view, *uv) - expected));
            points++;
        }
    }
    // (b) Pixel centres: each ray intersected with the plane here, texture at that point.
    double max_error_b = 0;
    int pixels = 0;
    for (int v = 40; v < 440; v += 5) {
        for (int u = 100; u < 540; u += 7) {
            const auto ray = cam.unproject(Eigen::Vector2d(u, v));
            if (!ray || ray->z() < std::cos(mrpt::DEG2RAD(60.0))) continue;
            const mrpt::math::TPoint3D d = kCameraPose.rotateVector({ray->x(), ray->y(), ray->z()});
            const double lambda = (1.2 - kCameraPose.z()) / d.z;
            const double x = kCameraPose.x() + lambda * d.x, y = kCameraPose.y() + lambda * d.y;
            const double expected = bilinear(texture, (x + 5) * kPpm - 0.5, (y + 5) * kPpm - 0.5);
            const size_t k = static_cast<size_t>(v) * cam.width + static_cast<size_t>(u);
            EXPECT_EQ(view.face[k], 0);
            max_error_b = std::max(max_error_b, std::abs(view.radiance[k] - expected));
            pixels++;
        }
    }
    std::cout << points << " plane points: max |image(project(P)) - texture(P)| = " << max_error_a
              << "; " << pixels
              << " pixel centres: max |pixel - texture(ray hit)| = " << max_error_b << "\n";
    EXPECT_GE(points, 150);
    EXPECT_GE(pixels, 1000);
    EXPECT_LT(max_error_a, 1.0);  // image gradient ≤ ~4 gray/px, interpolated between pixels
    EXPECT_LT(max_error_b, 1e-3);
}

TEST(OmniRenderer, OutsideTheImageCircleAndWhereNothingIsHitPixelsAreZero)
{
    cv::Mat texture(200, 200, CV_8UC1, cv::Scalar(200));
    TexturedScene scene;
    scene.rectangles.push_back(ceilingPlane(1.2, texture));
    OmniRenderer renderer;
    renderer.setCamera(testCamera());
    renderer.noise_std = 5;
    renderer.reset(7);
    const mrpt::img::CImage image = renderer.render(scene, kCameraPose);
    const cv::Mat& gray = image.asCvMatRef();
    const auto& cam = renderer.camera();
    ASSERT_EQ(gray.cols, 640);
    ASSERT_EQ(gray.rows, 480);
    ASSERT_EQ(gray.type(), CV_8UC1);

    size_t outside = 0, outside_nonzero = 0, below = 0, below_nonzero = 0, hit = 0;
    double hit_sum = 0, hit_sq = 0;
    for (int v = 0; v < cam.height; v++) {
        for (int u = 0; u < cam.width; u++) {
            const int value = gray.at<uint8_t>(v, u);
            const auto ray = cam.unproject(Eigen::Vector2d(u, v));
            if (!ray) {
                outside++, outside_nonzero += value != 0;
            } else if (ray->z() < -1e-9) {  // below the camera's horizon: misses the plane
                below++, below_nonzero += value != 0;
            } else if (ray->z() > 0.5) {  // θ < 60°: well inside the plane's extent
                hit++, hit_sum += value, hit_sq += value * value;
            }
        }
    }
    // Image circle: radius f·sin θ / (cos θ + ξ) at θ = 100°.
    const double t = cam.max_theta;
    const double radius = cam.fx * std::sin(t) / (std::cos(t) + cam.xi);
    const double valid = static_cast<double>(cam.width * cam.height) - outside;
    const double mean = hit_sum / hit, std = std::sqrt(hit_sq / hit - mean * mean);
    std::cout << "image circle radius " << radius << " px: " << valid
              << " valid pixels (pi r^2 = " << M_PI * radius * radius << "); " << below
              << " pixels below the horizon; plane pixels mean " << mean << ", std " << std << "\n";
    EXPECT_EQ(outside_nonzero, 0u);
    EXPECT_EQ(below_nonzero, 0u);
    EXPECT_GT(below, 20000u);
    EXPECT_NEAR(valid / (M_PI * radius * radius), 1.0, 0.01);
    EXPECT_NEAR(mean, 200, 0.1);
    EXPECT_NEAR(std, 5, 0.1);
    // The corners of the image are outside the circle.
    EXPECT_EQ(gray.at<uint8_t>(0, 0), 0);
    EXPECT_EQ(gray.at<uint8_t>(479, 639), 0);
}

TEST(OmniRenderer, TheNearestFaceHidesTheOthers)
{
    // A small dark square 0.5 m above the camera under a bright plane at 2 m.
    TexturedScene scene;
    scene.rectangles.push_back(ceilingPlane(2.0, cv::Mat(200, 200, CV_8UC1, cv::Scalar(220))));
    scene.rectangles.emplace_back(
        Eigen::Vector3d(-0.2, -0.2, 0.5), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 0.4,
        0.4, mrpt::img::CImage(cv::Mat(8, 8, CV_8UC1, cv::Scalar(30)), mrpt::img::DEEP_COPY), kPpm);
    OmniRenderer renderer;
    renderer.setCamera(testCamera());
    const mrpt::poses::CPose3D camera(0, 0, 0, 0, 0, 0);
    const TRenderedView view = renderer.renderView(scene, camera);
    const auto& cam = renderer.camera();
    size_t square = 0, wrong = 0;
    for (int v = 0; v < cam.height; v++) {
        for (int u = 0; u < cam.width; u++) {
            const auto ray = cam.unproject(Eigen::Vector2d(u, v));
            if (!ray || ray->z() < 0.5) continue;  // θ < 60°: within the far plane's extent
            const double x = 0.5 * ray->x() / ray->z(), y = 0.5 * ray->y() / ray->z();
            if (std::max(std::abs(x), std::abs(y)) > 0.199 &&
                std::max(std::abs(x), std::abs(y)) < 0.201)
                continue;  // on the square's border
            const bool in_square = std::max(std::abs(x), std::abs(y)) < 0.2;
            const size_t k = static_cast<size_t>(v) * cam.width + static_cast<size_t>(u);
            square += in_square;
            wrong += view.face[k] != (in_square ? 1 : 0) ||
                     std::abs(view.radiance[k] - (in_square ? 30.0f : 220.0f)) > 1e-3f;
        }
    }
    std::cout << square << " pixels see the near square, " << wrong << " wrong pixels\n";
    EXPECT_GT(square, 1000u);
    EXPECT_EQ(wrong, 0u);
}

TEST(OmniRenderer, SameSeedSameImageOtherSeedOtherNoise)
{
    TexturedScene scene;
    scene.rectangles.push_back(ceilingPlane(1.2, smoothTexture(200, 200)));
    OmniRenderer a, b;
    a.setCamera(testCamera());
    b.setCamera(testCamera());
    a.reset(3);
    b.reset(3);
    const cv::Mat ia = a.render(scene, kCameraPose).asCvMatRef().clone();
    EXPECT_EQ(cv::norm(ia, b.render(scene, kCameraPose).asCvMatRef(), cv::NORM_L1), 0.0);
    b.reset(4);
    EXPECT_GT(cv::norm(ia, b.render(scene, kCameraPose).asCvMatRef(), cv::NORM_L1), 0.0);
}
