#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <mrpt_vslam/sim/StereoRenderer.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iostream>
#include <opencv2/imgproc.hpp>

using namespace mrpt_vslam::sim;

namespace {

constexpr double kPpm = 200;  // texels per metre of the test boards

/// Checkerboard texture of `cols` × `rows` cells of `cell` [m], black and white.
mrpt::img::CImage checkerboard(int cols, int rows, double cell)
{
    const int c = static_cast<int>(std::lround(cell * kPpm));
    cv::Mat mat(rows * c, cols * c, CV_8UC1);
    for (int r = 0; r < mat.rows; r++)
        for (int k = 0; k < mat.cols; k++) mat.at<uint8_t>(r, k) = ((r / c + k / c) % 2) ? 230 : 25;
    return mrpt::img::CImage(mat, mrpt::img::DEEP_COPY);
}

/** A scene with one 12 × 9 checkerboard rectangle of `cell` [m] cells; `corners` receives its
 *  inner corners (world). */
TexturedScene boardScene(const Eigen::Vector3d& origin, const Eigen::Vector3d& axis_s,
                         const Eigen::Vector3d& axis_t, std::vector<Eigen::Vector3d>& corners,
                         double cell = 0.1)
{
    constexpr int kCols = 12, kRows = 9;
    const double kCell = cell;
    TexturedScene scene;
    scene.rectangles.emplace_back(origin, axis_s, axis_t, kCols * kCell, kRows * kCell,
                                  checkerboard(kCols, kRows, kCell), kPpm);
    for (int j = 1; j < kRows; j++)
        for (int i = 1; i < kCols; i++)
            corners.push_back(scene.rectangles.front().pointAt(i * kCell, j * kCell));
    return scene;
}

struct TCornerErrors {
    double max = 0, rms = 0;
    size_t count = 0;
};

/** Finds each corner with cv::cornerSubPix, started 0.7 px away from where the pinhole model
 *  projects it, and returns the distances between found and projected positions. */
TCornerErrors cornerErrors(const StereoRenderer& cam, const mrpt::img::CImage& image,
                           const mrpt::poses::CPose3D& camera_in_world,
                           const std::vector<Eigen::Vector3d>& corners)
{
    std::vector<cv::Point2f> expected, found;
    for (const Eigen::Vector3d& c : corners) {
        const auto p =
            camera_in_world.inverseComposePoint(mrpt::math::TPoint3D(c.x(), c.y(), c.z()));
        const Eigen::Vector2d uv = cam.project({p.x, p.y, p.z});
        if (uv.x() < 8 || uv.y() < 8 || uv.x() > cam.width - 9 || uv.y() > cam.height - 9) continue;
        expected.emplace_back(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
        found.emplace_back(static_cast<float>(uv.x() + 0.5), static_cast<float>(uv.y() - 0.5));
    }
    cv::cornerSubPix(image.asCvMatRef(), found, cv::Size(4, 4), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-4));
    TCornerErrors e;
    e.count = found.size();
    for (size_t i = 0; i < found.size(); i++) {
        const double d = std::hypot(found[i].x - expected[i].x, found[i].y - expected[i].y);
        e.max = std::max(e.max, d);
        e.rms += d * d;
    }
    e.rms = e.count ? std::sqrt(e.rms / e.count) : 0;
    std::cout << "corners " << e.count << ": max " << e.max << " px, rms " << e.rms << " px\n";
    return e;
}

}  // namespace

TEST(StereoRenderer, FieldOfViewOfTheVidereHeadSetting)
{
    StereoRenderer cam;
    const Eigen::Vector2d fov = cam.fieldOfViewDeg();
    EXPECT_NEAR(fov.x(), 2 * mrpt::RAD2DEG(std::atan(160.0 / 280.0)), 1e-9);  // 59.49°
    EXPECT_NEAR(fov.y(), 2 * mrpt::RAD2DEG(std::atan(120.0 / 280.0)), 1e-9);  // 46.40°
    const mrpt::img::TStereoCamera stereo = cam.stereoCamera();
    EXPECT_EQ(stereo.leftCamera.fx(), 280);
    EXPECT_EQ(stereo.rightCamera.cx(), 159.5);
    EXPECT_EQ(stereo.rightCameraPose.x, 0.12);
    EXPECT_EQ(stereo.rightCameraPose.qr, 1);
}

TEST(StereoRenderer, FrontoParallelCornersLandWherePinholeAndDisparityPutThem)
{
    StereoRenderer cam;
    cam.noise_std = 1.0;
    cam.reset(3);
    constexpr double kZ = 2.0;
    std::vector<Eigen::Vector3d> corners;
    // Camera frame = world frame; the board faces the camera (normal −z), off-centre on purpose.
    const TexturedScene scene =
        boardScene({-0.63, -0.47, kZ}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), corners);
    const mrpt::poses::CPose3D left_pose;
    const auto [left, right] = cam.render(scene, left_pose);

    const TCornerErrors l = cornerErrors(cam, left, left_pose, corners);
    const TCornerErrors r = cornerErrors(cam, right, left_pose + cam.rightCameraInLeft(), corners);
    EXPECT_GE(l.count, 80u);
    EXPECT_GE(r.count, 80u);
    EXPECT_LT(l.max, 0.2) << "rms " << l.rms;
    EXPECT_LT(r.max, 0.2) << "rms " << r.rms;
    EXPECT_LT(l.rms, 0.1);
    EXPECT_LT(r.rms, 0.1);

    // The right image is the left one shifted by the disparity f·b/Z = 16.8 px.
    const Eigen::Vector2d uv = cam.project(corners[20]);
    const Eigen::Vector2d uv_right = cam.project(corners[20] - Eigen::Vector3d(0.12, 0, 0));
    EXPECT_NEAR(uv.x() - uv_right.x(), cam.fx * cam.baseline / kZ, 1e-12);
    EXPECT_EQ(uv.y(), uv_right.y());
}

TEST(StereoRenderer, FarBoardSampledFromTheMipmapsKeepsItsCorners)
{
    StereoRenderer cam;
    cam.noise_std = 1.0;
    cam.reset(6);
    // At 5 m a sub-pixel spans 1.8 texels: trilinear sampling between mipmap levels 0 and 1.
    std::vector<Eigen::Vector3d> corners;
    const TexturedScene scene = boardScene({-1.13, -0.86, 5.0}, Eigen::Vector3d::UnitX(),
                                           Eigen::Vector3d::UnitY(), corners, 0.2);
    const mrpt::poses::CPose3D left_pose;
    const auto [left, right] = cam.render(scene, left_pose);
    const TCornerErrors l = cornerErrors(cam, left, left_pose, corners);
    const TCornerErrors r = cornerErrors(cam, right, left_pose + cam.rightCameraInLeft(), corners);
    EXPECT_GE(l.count, 80u);
    EXPECT_LT(l.max, 0.3) << "rms " << l.rms;
    EXPECT_LT(r.max, 0.3) << "rms " << r.rms;
}

TEST(StereoRenderer, SlantedBoardCornersLandWhereThePinholeModelPutsThem)
{
    StereoRenderer cam;
    cam.noise_std = 1.0;
    cam.reset(4);
    // Board turned 40° about the vertical axis, 1.4-2.2 m away: depth and foreshortening vary
    // across it. The camera looks along +y of the world (MRPT camera on a robot heading +y).
    const double a = mrpt::DEG2RAD(40.0);
    std::vector<Eigen::Vector3d> corners;
    const TexturedScene scene = boardScene({-0.55, 1.4, 0.95}, {std::cos(a), std::sin(a), 0},
                                           -Eigen::Vector3d::UnitZ(), corners);
    const mrpt::poses::CPose3D robot(0, 0, 0, mrpt::DEG2RAD(90.0), 0, 0);
    const mrpt::poses::CPose3D camera_on_robot(0, 0, 0.5, mrpt::DEG2RAD(-90.0), 0,
                                               mrpt::DEG2RAD(-90.0));
    const mrpt::poses::CPose3D left_pose = robot + camera_on_robot;
    const auto [left, right] = cam.render(scene, left_pose);

    const TCornerErrors l = cornerErrors(cam, left, left_pose, corners);
    const TCornerErrors r = cornerErrors(cam, right, left_pose + cam.rightCameraInLeft(), corners);
    EXPECT_GE(l.count, 60u);
    EXPECT_GE(r.count, 60u);
    EXPECT_LT(l.max, 0.5) << "rms " << l.rms;
    EXPECT_LT(r.max, 0.5) << "rms " << r.rms;
    EXPECT_LT(l.rms, 0.2);
    EXPECT_LT(r.rms, 0.2);
}

TEST(StereoRenderer, EmptySceneIsBackgroundPlusTheConfiguredNoise)
{
    StereoRenderer cam;
    cam.noise_std = 2.0;
    cam.reset(5);
    const TexturedScene empty;
    const TRenderedView view = cam.renderView(empty, mrpt::poses::CPose3D());
    for (size_t i = 0; i < view.radiance.size(); i++) {
        ASSERT_EQ(view.radiance[i], 128.0f);
        ASSERT_EQ(view.face[i], -1);
    }
    const auto [left, right] = cam.render(empty, mrpt::poses::CPose3D());
    for (const mrpt::img::CImage* img : {&left, &right}) {
        cv::Scalar mean, stddev;
        cv::meanStdDev(img->asCvMatRef(), mean, stddev);
        EXPECT_NEAR(mean[0], 128.0, 0.05);
        // σ² + 1/12 of the rounding to 8 bits
        EXPECT_NEAR(stddev[0], std::sqrt(4.0 + 1.0 / 12), 0.03);
    }
    EXPECT_FALSE(cv::countNonZero(left.asCvMatRef() != right.asCvMatRef()) == 0)
        << "left and right images must get different noise";
}

TEST(StereoRenderer, SeesPointOnlyInsideBothImagesAndUnoccluded)
{
    StereoRenderer cam;
    std::vector<Eigen::Vector3d> corners;
    const TexturedScene scene =
        boardScene({-0.6, -0.45, 2.0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), corners);
    const mrpt::poses::CPose3D pose;
    EXPECT_TRUE(cam.seesPoint(scene, pose, corners[40], 3));
    // Behind the board: hidden; in front of it: seen.
    EXPECT_FALSE(cam.seesPoint(scene, pose, {0.0, 0.0, 3.0}, 3));
    EXPECT_TRUE(cam.seesPoint(scene, pose, {0.0, 0.0, 1.0}, 3));
    // Behind the camera, and outside the right image only (left border region).
    EXPECT_FALSE(cam.seesPoint(scene, pose, {0.0, 0.0, -1.0}, 3));
    const double z = 1.0, u_left = 10;  // 10 px from the left border of the left image
    const Eigen::Vector3d p((u_left - cam.cx) * z / cam.fx, 0, z);
    EXPECT_FALSE(cam.seesPoint(scene, pose, p, 3)) << "disparity 33.6 px puts it outside";
    EXPECT_TRUE(cam.seesPoint(scene, pose, p + Eigen::Vector3d(0.2, 0, 0), 3));
}
