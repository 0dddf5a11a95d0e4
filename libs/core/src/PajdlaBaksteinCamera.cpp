#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt_vslam/core/ConfigSectionWriter.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/core/PajdlaBaksteinCamera.h>

#include <algorithm>
#include <cmath>

namespace mrpt_vslam::core {

double PajdlaBaksteinCamera::radius(double theta) const
{
    // Eq. 1, first line
    return a * std::tan(theta / b) + c * std::sin(theta / d);
}

double PajdlaBaksteinCamera::radiusDerivative(double theta) const
{
    const double ct = std::cos(theta / b);
    return a / (b * ct * ct) + (c / d) * std::cos(theta / d);
}

double PajdlaBaksteinCamera::increasingUpTo(double theta_max) const
{
    constexpr int kSteps = 1000;
    for (int i = 0; i <= kSteps; i++) {
        if (!(radiusDerivative(theta_max * i / kSteps) > 0))
            return theta_max * std::max(i - 1, 0) / kSteps;
    }
    return theta_max;
}

Eigen::Vector2d PajdlaBaksteinCamera::project(double phi, double theta) const
{
    const double r = radius(theta);
    // Eq. 1, second and third lines
    return {u0 + r * std::cos(phi), beta * (v0 + r * std::sin(phi))};
}

Eigen::Matrix2d PajdlaBaksteinCamera::projectJacobian(double phi, double theta) const
{
    const double r = radius(theta), dr = radiusDerivative(theta);
    const double cp = std::cos(phi), sp = std::sin(phi);
    Eigen::Matrix2d J;
    J << -r * sp, dr * cp, beta * r * cp, beta * dr * sp;
    return J;
}

bool PajdlaBaksteinCamera::isInsideImage(const Eigen::Vector2d& uv) const
{
    return uv.x() >= 0 && uv.y() >= 0 && uv.x() <= width - 1 && uv.y() <= height - 1;
}

bool PajdlaBaksteinCamera::isVisible(double phi, double theta) const
{
    return theta >= 0 && theta <= max_theta && isInsideImage(project(phi, theta));
}

Eigen::Vector2d PajdlaBaksteinCamera::anglesOfPoint(const mrpt::math::TPoint3D& p)
{
    return {std::atan2(p.y, p.x), std::atan2(std::hypot(p.x, p.y), p.z)};
}

void PajdlaBaksteinCamera::validate() const
{
    constexpr const char* kOwner = "PajdlaBaksteinCamera";
    requireParameter(b > 0, kOwner, "b", b, "must be > 0");
    requireParameter(d > 0, kOwner, "d", d, "must be > 0");
    requireParameter(beta > 0, kOwner, "beta", beta, "must be > 0");
    requireParameter(width > 0, kOwner, "width", width, "must be > 0");
    requireParameter(height > 0, kOwner, "height", height, "must be > 0");
    const double maxThetaDeg = mrpt::RAD2DEG(max_theta);
    requireParameter(max_theta > 0 && max_theta < M_PI, kOwner, "max_theta_deg", maxThetaDeg,
                     "must be in (0, 180)");
    // r(θ) must be strictly increasing on [0, max_theta] or the model is not invertible.
    requireParameter(
        max_theta < b * M_PI / 2, kOwner, "max_theta_deg", maxThetaDeg,
        mrpt::format("must be below b * 90 = %g (the tan term diverges there)", b * 90));
    requireParameter(increasingUpTo(max_theta) == max_theta, kOwner, "max_theta_deg", maxThetaDeg,
                     "is past the angle where r(theta) stops increasing");
}

void PajdlaBaksteinCamera::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                              const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(a, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(b, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(c, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(d, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(u0, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(v0, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(beta, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(width, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(height, int, cfg, section);
    max_theta = mrpt::DEG2RAD(cfg.read_double(section, "max_theta_deg", mrpt::RAD2DEG(max_theta)));
    validate();
}

void PajdlaBaksteinCamera::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                            const std::string& section) const
{
    const ConfigSectionWriter put(cfg, section);
    put("a", a, "[px] tan-term gain of Eq. 1");
    put("b", b, "[-] tan-term angle divisor");
    put("c", c, "[px] sin-term gain");
    put("d", d, "[-] sin-term angle divisor");
    put("u0", u0, "[px] image centre column");
    put("v0", v0, "[px] image centre row (before beta)");
    put("beta", beta, "[-] pixel aspect ratio");
    put("width", width, "[px] image width");
    put("height", height, "[px] image height");
    put("max_theta_deg", mrpt::RAD2DEG(max_theta), "[deg] field-of-view half angle");
}

}  // namespace mrpt_vslam::core
