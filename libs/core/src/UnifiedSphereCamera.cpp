#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt_vslam/core/ConfigSectionWriter.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/core/UnifiedSphereCamera.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mrpt_vslam::core {
std::optional<Eigen::Vector2d> UnifiedSphereCamera::project(const Eigen::Vector3d& ray) const
{
    const double n = ray.norm();
    // Field of view: θ ≤ max_theta ⇔ z / |X| ≥ cos(max_theta); this also keeps z_s + ξ > 0.
    if (!(n > 0) || ray.z() < n * std::cos(max_theta)) return std::nullopt;
    // Steps 1-2: sphere, then the normalised plane seen from (0, 0, −ξ).
    const double d = ray.z() + xi * n;
    const double mx = ray.x() / d, my = ray.y() / d;
    // Step 3: generalised camera matrix.
    const Eigen::Vector2d uv(fx * mx + skew * my + cx, fy * my + cy);
    if (!isInsideImage(uv)) return std::nullopt;
    return uv;
}

Eigen::Matrix<double, 2, 3> UnifiedSphereCamera::projectJacobian(const Eigen::Vector3d& point) const
{
    const double n = point.norm();
    const double d = point.z() + xi * n;
    const double mx = point.x() / d, my = point.y() / d;
    // ∂d/∂X = ξ X / |X| + e_z;  ∂m/∂X = (e_xy − m ∂d/∂X) / d.
    Eigen::RowVector3d dd = (xi / n) * point.transpose();
    dd.z() += 1;
    Eigen::Matrix<double, 2, 3> dm;
    dm.row(0) = -mx * dd;
    dm.row(1) = -my * dd;
    dm(0, 0) += 1;
    dm(1, 1) += 1;
    dm /= d;
    Eigen::Matrix2d K;
    K << fx, skew, 0, fy;
    return K * dm;
}

std::optional<Eigen::Vector3d> UnifiedSphereCamera::unproject(const Eigen::Vector2d& pixel) const
{
    if (!isInsideImage(pixel)) return std::nullopt;
    const double my = (pixel.y() - cy) / fy;
    const double mx = (pixel.x() - cx - skew * my) / fx;
    const double r2 = mx * mx + my * my;
    // Back onto the unit sphere (closed form); no real solution past the model's limit (ξ > 1).
    const double disc = 1 + (1 - xi * xi) * r2;
    if (disc < 0) return std::nullopt;
    const double eta = (xi + std::sqrt(disc)) / (1 + r2);
    const Eigen::Vector3d ray(eta * mx, eta * my, eta - xi);
    if (ray.z() < std::cos(max_theta)) return std::nullopt;
    return ray;
}

bool UnifiedSphereCamera::isInsideImage(const Eigen::Vector2d& uv) const
{
    return uv.x() >= 0 && uv.y() >= 0 && uv.x() <= width - 1 && uv.y() <= height - 1;
}

double UnifiedSphereCamera::modelLimit() const
{
    // ρ(θ) = sin θ / (cos θ + ξ) is increasing while cos θ > −ξ and cos θ > −1/ξ.
    return std::acos(-(xi > 1 ? 1 / xi : xi));
}

void UnifiedSphereCamera::validate() const
{
    constexpr const char* kOwner = "UnifiedSphereCamera";
    requireParameter(std::isfinite(xi) && xi >= 0, kOwner, "xi", xi, "must be >= 0");
    requireParameter(std::isfinite(fx) && fx > 0, kOwner, "fx", fx, "must be > 0");
    requireParameter(std::isfinite(fy) && fy > 0, kOwner, "fy", fy, "must be > 0");
    requireParameter(std::isfinite(cx), kOwner, "cx", cx, "must be finite");
    requireParameter(std::isfinite(cy), kOwner, "cy", cy, "must be finite");
    requireParameter(std::isfinite(skew), kOwner, "skew", skew, "must be finite");
    requireParameter(width > 0, kOwner, "width", width, "must be > 0");
    requireParameter(height > 0, kOwner, "height", height, "must be > 0");
    const double limit = modelLimit();
    requireParameter(
        max_theta > 0 && max_theta < limit, kOwner, "max_theta_deg", mrpt::RAD2DEG(max_theta),
        mrpt::format("must be in (0, %g) for xi = %g (the model is not one-to-one beyond)",
                     mrpt::RAD2DEG(limit), xi));
}

void UnifiedSphereCamera::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                             const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(xi, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(fx, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(fy, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(cx, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(cy, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(skew, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(width, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(height, int, cfg, section);
    max_theta = mrpt::DEG2RAD(cfg.read_double(section, "max_theta_deg", mrpt::RAD2DEG(max_theta)));
    validate();
}

void UnifiedSphereCamera::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                           const std::string& section) const
{
    const ConfigSectionWriter put(cfg, section);
    put("xi", xi, "[-] mirror parameter (0 pinhole, 1 parabolic)");
    put("fx", fx, "[px] generalised focal length gamma1 (columns)");
    put("fy", fy, "[px] generalised focal length gamma2 (rows)");
    put("cx", cx, "[px] principal point column");
    put("cy", cy, "[px] principal point row");
    put("skew", skew, "[px] skew of the camera matrix");
    put("width", width, "[px] image width");
    put("height", height, "[px] image height");
    put("max_theta_deg", mrpt::RAD2DEG(max_theta), "[deg] largest angle from the optical axis");
}

}  // namespace mrpt_vslam::core
