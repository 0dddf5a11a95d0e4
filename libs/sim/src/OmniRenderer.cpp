#include <mrpt_vslam/sim/ConfigReading.h>
#include <mrpt_vslam/sim/OmniRenderer.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

namespace mrpt_vslam::sim {

void OmniRenderer::setCamera(const core::UnifiedSphereCamera& camera)
{
    camera.validate();
    m_camera = camera;
    const size_t n = static_cast<size_t>(camera.width) * static_cast<size_t>(camera.height);
    m_rays.assign(n, Eigen::Vector3d::Zero());
    m_pixel_angle.assign(n, 0.0);
    for (int v = 0; v < camera.height; v++) {
        for (int u = 0; u < camera.width; u++) {
            const auto ray = camera.unproject(Eigen::Vector2d(u, v));
            if (!ray) continue;
            const size_t k = static_cast<size_t>(v) * camera.width + static_cast<size_t>(u);
            m_rays[k] = *ray;
            // J has the ray as null vector: √det(J·Jᵀ) [px²/rad²] is the pixel density.
            const Eigen::Matrix<double, 2, 3> J = camera.projectJacobian(*ray);
            const Eigen::Matrix2d JJt = J * J.transpose();
            m_pixel_angle[k] = 1.0 / std::pow(JJt.determinant(), 0.25);
        }
    }
}

TRenderedView OmniRenderer::renderView(const TexturedScene& scene,
                                       const mrpt::poses::CPose3D& camera_in_world) const
{
    const Eigen::Matrix3d R = camera_in_world.getRotationMatrix().asEigen();
    const Eigen::Vector3d C(camera_in_world.x(), camera_in_world.y(), camera_in_world.z());

    // Bounding cone of each face (camera frame): axis and cosine of the half angle; faces whose
    // bounding sphere holds the camera get cos = −2 (every ray is tested).
    const size_t faces = scene.rectangles.size();
    std::vector<Eigen::Vector3d> cone_axis(faces, Eigen::Vector3d::Zero());
    std::vector<double> cone_cos(faces, -2.0);
    for (size_t id = 0; id < faces; id++) {
        const TexturedRectangle& rect = scene.rectangles[id];
        const Eigen::Vector3d to_centre = rect.pointAt(rect.width() / 2, rect.height() / 2) - C;
        const double dist = to_centre.norm();
        const double radius = 0.5 * std::hypot(rect.width(), rect.height()) + 1e-6;
        if (dist <= radius) continue;
        cone_axis[id] = R.transpose() * to_centre / dist;
        cone_cos[id] = std::sqrt(1 - (radius / dist) * (radius / dist));
    }

    TRenderedView view;
    view.width = m_camera.width;
    view.height = m_camera.height;
    view.radiance.assign(m_rays.size(), 0.0f);
    view.face.assign(m_rays.size(), -1);
    for (size_t k = 0; k < m_rays.size(); k++) {
        const Eigen::Vector3d& r = m_rays[k];
        if (m_pixel_angle[k] == 0) continue;
        const Eigen::Vector3d d = R * r;
        double best = std::numeric_limits<double>::infinity();
        int best_id = -1;
        for (size_t id = 0; id < faces; id++) {
            if (r.dot(cone_axis[id]) < cone_cos[id]) continue;
            const std::optional<double> lambda = scene.rectangles[id].intersect(C, d);
            if (lambda && *lambda < best) best = *lambda, best_id = static_cast<int>(id);
        }
        if (best_id < 0) continue;
        const TexturedRectangle& rect = scene.rectangles[static_cast<size_t>(best_id)];
        const Eigen::Vector3d q = C + best * d - rect.origin();
        const double cos_incidence = std::abs(rect.normal().dot(d));
        const double footprint = rect.pixelsPerMetre() * best * m_pixel_angle[k] /
                                 std::sqrt(std::max(cos_incidence, 0.01));
        view.radiance[k] = rect.sample(q.dot(rect.axisS()), q.dot(rect.axisT()), footprint);
        view.face[k] = best_id;
    }
    return view;
}

mrpt::img::CImage OmniRenderer::render(const TexturedScene& scene,
                                       const mrpt::poses::CPose3D& camera_in_world)
{
    const TRenderedView view = renderView(scene, camera_in_world);
    mrpt::img::CImage image = addPixelNoise(view, noise_std, m_rng);
    cv::Mat& gray = image.asCvMatRef();
    for (int v = 0; v < view.height; v++) {
        uint8_t* row = gray.ptr<uint8_t>(v);
        for (int u = 0; u < view.width; u++)
            if (view.face[static_cast<size_t>(v) * view.width + static_cast<size_t>(u)] < 0)
                row[u] = 0;
    }
    return image;
}

void OmniRenderer::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                      const std::string& s)
{
    core::UnifiedSphereCamera camera = m_camera;
    camera.loadFromConfigFile(cfg, s);
    MRPT_LOAD_CONFIG_VAR(noise_std, double, cfg, s);
    checkConfig(noise_std >= 0, s, "noise_std", ">= 0");
    setCamera(camera);
}

}  // namespace mrpt_vslam::sim
