#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/UnifiedSphereCamera.h>

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <vector>

namespace mrpt_vslam::viewmap::test {

/** Synthetic scenes for the planar epipolar geometry: a robot pose, a view pose and 3-D points
 *  seen from both, with the camera at each pose's origin, z up. */
struct TPlanarScene {
    mrpt::math::TPose2D robot;
    mrpt::math::TPose2D view;
    std::vector<Eigen::Vector3d> points;  ///< world frame [m]
};

struct TSceneOptions {
    size_t points = 100;
    double min_baseline = 0.3, max_baseline = 2.0;  ///< [m] robot-view distance
    double min_range = 1.5, max_range = 8.0;        ///< [m] horizontal distance to both poses
    double min_height = -0.4, max_height = 2.5;     ///< [m] relative to the camera
    double max_elevation = 25.0 * M_PI / 180;       ///< [rad] above the horizon, from both poses
};

/// Unit ray of the world point P from the planar pose (camera at the pose's origin, z up).
inline Eigen::Vector3d rayFrom(const mrpt::math::TPose2D& pose, const Eigen::Vector3d& P)
{
    const double c = std::cos(pose.phi), s = std::sin(pose.phi);
    const double dx = P.x() - pose.x, dy = P.y() - pose.y;
    return Eigen::Vector3d(c * dx + s * dy, -s * dx + c * dy, P.z()).normalized();
}

/// Random poses (any headings) and points visible from both.
inline TPlanarScene randomScene(mrpt::random::CRandomGenerator& rng, const TSceneOptions& opt = {})
{
    TPlanarScene scene;
    scene.robot = {rng.drawUniform(-5.0, 5.0), rng.drawUniform(-5.0, 5.0),
                   rng.drawUniform(-M_PI, M_PI)};
    const double baseline = rng.drawUniform(opt.min_baseline, opt.max_baseline);
    const double direction = rng.drawUniform(-M_PI, M_PI);
    scene.view = {scene.robot.x + baseline * std::cos(direction),
                  scene.robot.y + baseline * std::sin(direction), rng.drawUniform(-M_PI, M_PI)};
    const double mx = 0.5 * (scene.robot.x + scene.view.x);
    const double my = 0.5 * (scene.robot.y + scene.view.y);
    while (scene.points.size() < opt.points) {
        const double range = rng.drawUniform(opt.min_range, opt.max_range);
        const double angle = rng.drawUniform(-M_PI, M_PI);
        const Eigen::Vector3d P(mx + range * std::cos(angle), my + range * std::sin(angle),
                                rng.drawUniform(opt.min_height, opt.max_height));
        bool ok = true;
        for (const auto& pose : {scene.robot, scene.view}) {
            const double horizontal = std::hypot(P.x() - pose.x, P.y() - pose.y);
            ok = ok && horizontal >= opt.min_range &&
                 std::atan2(P.z(), horizontal) <= opt.max_elevation;
        }
        if (ok) scene.points.push_back(P);
    }
    return scene;
}

/// Rays of all points from `pose`, one column each.
inline Eigen::Matrix3Xd raysFrom(const mrpt::math::TPose2D& pose,
                                 const std::vector<Eigen::Vector3d>& points)
{
    Eigen::Matrix3Xd rays(3, Eigen::Index(points.size()));
    for (size_t k = 0; k < points.size(); k++) rays.col(Eigen::Index(k)) = rayFrom(pose, points[k]);
    return rays;
}

/** The ray as measured by an omnidirectional camera under a mirror (UnifiedSphereCamera, +z of
 *  the camera pointing down): projected to a pixel, disturbed by N(0, σ²) in each coordinate,
 *  lifted back and turned into the robot frame. nullopt if the pixel leaves the image. */
inline std::optional<Eigen::Vector3d> measuredRay(const core::UnifiedSphereCamera& camera,
                                                  const Eigen::Vector3d& ray, double sigma_px,
                                                  mrpt::random::CRandomGenerator& rng)
{
    // Camera frame: a half turn about x (z down, y mirrored).
    const Eigen::Vector3d in_camera(ray.x(), -ray.y(), -ray.z());
    const auto uv = camera.project(in_camera);
    if (!uv) return std::nullopt;
    const Eigen::Vector2d noisy(uv->x() + rng.drawGaussian1D(0.0, sigma_px),
                                uv->y() + rng.drawGaussian1D(0.0, sigma_px));
    const auto back = camera.unproject(noisy);
    if (!back) return std::nullopt;
    return Eigen::Vector3d(back->x(), -back->y(), -back->z());
}

/// Wrapped difference a − b in (−π, π].
inline double angleError(double a, double b) { return std::remainder(a - b, 2 * M_PI); }

}  // namespace mrpt_vslam::viewmap::test
