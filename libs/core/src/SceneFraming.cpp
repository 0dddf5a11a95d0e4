#include <mrpt/core/bits_math.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/opengl/CPointCloudColoured.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/opengl/CSetOfTriangles.h>
#include <mrpt/opengl/CSphere.h>
#include <mrpt/opengl/CText.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt_vslam/core/SceneFraming.h>

#include <algorithm>
#include <cmath>

namespace mrpt_vslam::core {
namespace {
/// Adds to `box` what sceneContentBox() counts of `obj`, placed at `parent` ⊕ its own pose.
void addContent(const mrpt::opengl::CRenderizable& obj, const mrpt::poses::CPose3D& parent,
                std::optional<mrpt::math::TBoundingBox>& box)
{
    using namespace mrpt::opengl;
    const mrpt::poses::CPose3D pose = parent + mrpt::poses::CPose3D(obj.getPose());
    const auto add = [&](const mrpt::math::TPoint3D& local) {
        const auto p = pose.composePoint(local);
        if (box)
            box->updateWithPoint(p);
        else
            box = mrpt::math::TBoundingBox(p, p);
    };
    if (const auto* group = dynamic_cast<const CSetOfObjects*>(&obj)) {
        for (const auto& child : *group)
            if (child) addContent(*child, pose, box);
        return;
    }
    if (dynamic_cast<const CSphere*>(&obj) || dynamic_cast<const CText*>(&obj)) {
        add({0, 0, 0});
        return;
    }
    const auto* lines = dynamic_cast<const CSetOfLines*>(&obj);
    const auto* triangles = dynamic_cast<const CSetOfTriangles*>(&obj);
    const auto* cloud = dynamic_cast<const CPointCloud*>(&obj);
    const auto* colouredCloud = dynamic_cast<const CPointCloudColoured*>(&obj);
    const bool hasVertices =
        (lines && !lines->empty()) || (triangles && triangles->getTrianglesCount() > 0) ||
        (cloud && !cloud->empty()) || (colouredCloud && !colouredCloud->empty());
    if (!hasVertices) return;
    const auto local = obj.getBoundingBoxLocal();
    for (int k = 0; k < 8; k++)
        add({(k & 1) ? local.max.x : local.min.x, (k & 2) ? local.max.y : local.min.y,
             (k & 4) ? local.max.z : local.min.z});
}
}  // namespace

std::optional<mrpt::math::TBoundingBox> sceneContentBox(const mrpt::opengl::COpenGLScene& scene)
{
    std::optional<mrpt::math::TBoundingBox> box;
    const auto view = scene.getViewport("main");
    if (!view) return box;
    for (const auto& obj : *view)
        if (obj) addContent(*obj, mrpt::poses::CPose3D(), box);
    return box;
}

double framingDistance(const mrpt::math::TBoundingBox& box, double azimuth_deg,
                       double elevation_deg, double fov_deg, double fill)
{
    const double az = mrpt::DEG2RAD(azimuth_deg), el = mrpt::DEG2RAD(elevation_deg);
    // the camera's axes, as mrpt::opengl::TRenderMatrices::applyLookAt() makes them
    const mrpt::math::TVector3D back(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                     std::sin(el));
    const mrpt::math::TVector3D right(-std::sin(az), std::cos(az), 0);
    const mrpt::math::TVector3D up(-std::sin(el) * std::cos(az), -std::sin(el) * std::sin(az),
                                   std::cos(el));
    const double slope = fill * std::tan(mrpt::DEG2RAD(fov_deg) / 2);
    const mrpt::math::TPoint3D centre = (box.min + box.max) * 0.5;
    const auto dot = [](const mrpt::math::TVector3D& a, const mrpt::math::TVector3D& b) {
        return a.x * b.x + a.y * b.y + a.z * b.z;
    };
    double distance = 0;
    for (int k = 0; k < 8; k++) {
        const mrpt::math::TVector3D q =
            mrpt::math::TPoint3D((k & 1) ? box.max.x : box.min.x, (k & 2) ? box.max.y : box.min.y,
                                 (k & 4) ? box.max.z : box.min.z) -
            centre;
        const double off_axis = std::max(std::abs(dot(q, right)), std::abs(dot(q, up)));
        distance = std::max(distance, dot(q, back) + off_axis / slope);
    }
    return distance;
}

void frameSceneOnContent(mrpt::opengl::COpenGLScene& scene)
{
    const auto box = sceneContentBox(scene);
    if (!box) return;
    constexpr double kAzimuthDeg = 225, kElevationDeg = 50, kFill = 0.9;
    // a single point still gets a view around it
    constexpr double kMinDistance = 1.0;
    auto& camera = scene.getViewport("main")->getCamera();
    camera.setPointingAt((box->min + box->max) * 0.5);
    camera.setAzimuthDegrees(static_cast<float>(kAzimuthDeg));
    camera.setElevationDegrees(static_cast<float>(kElevationDeg));
    camera.setZoomDistance(static_cast<float>(std::max(
        kMinDistance,
        framingDistance(*box, kAzimuthDeg, kElevationDeg, camera.getProjectiveFOVdeg(), kFill))));
    // SceneViewer3D takes the "main" viewport's camera only with this flag (else it keeps its own)
    scene.enableFollowCamera(true);
}

}  // namespace mrpt_vslam::core
