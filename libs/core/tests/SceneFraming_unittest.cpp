#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/opengl/CEllipsoid3D.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/opengl/CSphere.h>
#include <mrpt/opengl/CText.h>
#include <mrpt/opengl/TRenderMatrices.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/RunOutputs.h>
#include <mrpt_vslam/core/SceneFraming.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

using mrpt::math::TBoundingBox;
using mrpt::math::TPoint3D;
namespace core = mrpt_vslam::core;

namespace {

/** Largest |x|, |y| of the box's corners in normalized device coordinates of
 * MRPT's own camera (TRenderMatrices, square viewport) looking at the box's
 * centre from `distance`; infinity if a corner is behind the camera. */
double largestProjection(const TBoundingBox& box, double azimuth_deg, double elevation_deg,
                         double fov_deg, double distance)
{
    const double az = mrpt::DEG2RAD(azimuth_deg), el = mrpt::DEG2RAD(elevation_deg);
    mrpt::opengl::TRenderMatrices m;
    m.FOV = fov_deg;
    m.viewport_width = m.viewport_height = 500;
    m.pointing = (box.min + box.max) * 0.5;
    m.eye =
        m.pointing +
        TPoint3D(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)) * distance;
    m.up = {0, 0, 1};
    m.computeProjectionMatrix(0.01f, 1e4f);
    m.applyLookAt();
    double largest = 0;
    for (int k = 0; k < 8; k++) {
        const Eigen::Vector4f corner(static_cast<float>((k & 1) ? box.max.x : box.min.x),
                                     static_cast<float>((k & 2) ? box.max.y : box.min.y),
                                     static_cast<float>((k & 4) ? box.max.z : box.min.z), 1);
        const Eigen::Vector4f h = m.p_matrix.asEigen() * m.v_matrix.asEigen() * corner;
        if (h[3] <= 0) return std::numeric_limits<double>::infinity();
        largest = std::max({largest, std::abs(double(h[0] / h[3])), std::abs(double(h[1] / h[3]))});
    }
    return largest;
}

}  // namespace

TEST(SceneFraming, ContentBoxHasLinesPointsSpheresAndLabelsNotFloorOrEllipsoids)
{
    mrpt::opengl::COpenGLScene scene;
    EXPECT_FALSE(core::sceneContentBox(scene));
    scene.insert(mrpt::opengl::CGridPlaneXY::Create(-50, 50, -50, 50, 0, 1));
    EXPECT_FALSE(core::sceneContentBox(scene));

    // a group turned by 90° about z at (10, 0, 0): local (x, y) lands on (10 - y,
    // x)
    auto group = mrpt::opengl::CSetOfObjects::Create();
    group->setPose(mrpt::poses::CPose3D(10, 0, 0, mrpt::DEG2RAD(90.0), 0, 0));
    auto lines = mrpt::opengl::CSetOfLines::Create();
    lines->appendLine(0, 0, 0, 2, 3, 1);  // → (10, 0, 0), (7, 2, 1)
    group->insert(lines);
    auto label = mrpt::opengl::CText::Create("end");
    label->setLocation(-1, 4, 0.5);  // → (6, -1, 0.5)
    group->insert(label);
    group->insert(mrpt::opengl::CSetOfLines::Create());  // empty: not at the group's origin
    scene.insert(group);
    auto cloud = mrpt::opengl::CPointCloud::Create();
    cloud->insertPoint(-3, -2, 0);
    cloud->insertPoint(1, 1, 2);
    scene.insert(cloud);
    auto sphere = mrpt::opengl::CSphere::Create(0.5f);
    sphere->setLocation(5, -6, 0.2);
    scene.insert(sphere);
    auto ellipsoid = mrpt::opengl::CEllipsoid3D::Create();
    auto cov = mrpt::math::CMatrixDouble33::Identity();
    cov *= 1e4;
    mrpt::math::CMatrixFixed<double, 3, 1> mean;
    mean.fill(100);
    ellipsoid->setCovMatrixAndMean(cov, mean);
    scene.insert(ellipsoid);

    const auto box = core::sceneContentBox(scene);
    ASSERT_TRUE(box);
    EXPECT_NEAR(box->min.x, -3, 1e-6);
    EXPECT_NEAR(box->min.y, -6, 1e-6);
    EXPECT_NEAR(box->min.z, 0, 1e-6);
    EXPECT_NEAR(box->max.x, 10, 1e-6);
    EXPECT_NEAR(box->max.y, 2, 1e-6);
    EXPECT_NEAR(box->max.z, 2, 1e-6);
}

TEST(SceneFraming, DistanceOfASquareSeenEdgeOnIsClosedForm)
{
    // from azimuth 0, elevation 0 the camera looks along -x: the nearest corners
    // (x = a) are at depth d - a, a to the side, so d = a + a / (fill tan(fov /
    // 2))
    const double a = 4, fill = 0.8;
    const TBoundingBox square({-a, -a, 0}, {a, a, 0});
    EXPECT_NEAR(core::framingDistance(square, 0, 0, 30, fill),
                a + a / (fill * std::tan(mrpt::DEG2RAD(15.0))), 1e-9);
}

TEST(SceneFraming, DistanceIsTheNearestThatShowsEveryCorner)
{
    const double fov = 30, fill = 0.9;
    const std::pair<double, double> views[] = {
        {225, 50}, {0, 45}, {100, 60}};  // azimuth, elevation
    for (const auto& box :
         {TBoundingBox({-3, -6, 0}, {10, 2, 2}), TBoundingBox({-10, -15, 0}, {40, 15, 3}),
          TBoundingBox({0, 0, 0}, {1, 20, 0})}) {
        for (const auto& [az, el] : views) {
            const double d = core::framingDistance(box, az, el, fov, fill);
            // at that distance the farthest-out corner is on the edge of the framed
            // part
            EXPECT_NEAR(largestProjection(box, az, el, fov, d), fill, 1e-4);
            // brute force: the first of steps of about 0.1% (none of them exactly d) at which every
            // corner is in
            const double step = d / 1000.5;
            double seen = 0;
            for (int i = 1; i <= 2001 && seen == 0; i++)
                if (largestProjection(box, az, el, fov, i * step) <= fill) seen = i * step;
            EXPECT_NEAR(seen, d, step) << "azimuth " << az << ", elevation " << el;
        }
    }
}

TEST(SceneFraming, SavedSceneOpensOnItsContent)
{
    const mrpt_vslam::test::ScratchFolder scratch("SceneFraming_unittest");
    mrpt::opengl::COpenGLScene scene;
    scene.insert(mrpt::opengl::CGridPlaneXY::Create(-50, 50, -50, 50, 0, 1));
    core::frameSceneOnContent(scene);
    EXPECT_FALSE(scene.followCamera());  // nothing to frame: SceneViewer3D keeps
                                         // its own camera

    core::TumTrajectory path;
    path.push_back(0, {20, -4, 0, 0, 0, 0});
    path.push_back(1, {30, 6, 0, 0, 0, 0});
    scene.insert(core::trajectoryAsLines(path, {0, 0.8f, 0}, "estimate"));
    core::frameSceneOnContent(scene);
    const auto file = scratch.file("framed.3Dscene");
    core::saveScene(scene, file);

    mrpt::opengl::COpenGLScene loaded;
    mrpt::io::CFileGZInputStream in(file);
    mrpt::serialization::archiveFrom(in) >> loaded;
    EXPECT_TRUE(loaded.followCamera());
    const auto& camera = loaded.getViewport("main")->getCamera();
    // the path's lines are 0.01 above the poses, its label 0.2 above the last one
    const TBoundingBox box({20, -4, 0.01}, {30, 6, 0.2});
    EXPECT_NEAR(camera.getPointingAtX(), 25, 1e-5);
    EXPECT_NEAR(camera.getPointingAtY(), 1, 1e-5);
    EXPECT_NEAR(camera.getPointingAtZ(), 0.105, 1e-5);
    EXPECT_NEAR(camera.getAzimuthDegrees(), 225, 1e-5);
    EXPECT_NEAR(camera.getElevationDegrees(), 50, 1e-5);
    EXPECT_NEAR(camera.getZoomDistance(), core::framingDistance(box, 225, 50, 30, 0.9), 1e-4);
    EXPECT_NEAR(camera.getProjectiveFOVdeg(), 30, 1e-6);
}
