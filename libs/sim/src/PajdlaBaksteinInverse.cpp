#include <mrpt_vslam/sim/PajdlaBaksteinInverse.h>

#include <algorithm>
#include <cmath>

namespace mrpt_vslam::sim {

namespace {
constexpr int kTableSize = 2048;
}

PajdlaBaksteinInverse::PajdlaBaksteinInverse(const core::PajdlaBaksteinCamera& camera)
    : m_camera(camera), m_step(camera.max_theta / (kTableSize - 1))
{
    m_radius_table.resize(kTableSize);
    for (int i = 0; i < kTableSize; i++) m_radius_table[i] = m_camera.radius(i * m_step);
}

double PajdlaBaksteinInverse::thetaOfRadius(double radius_px) const
{
    if (radius_px <= 0) return 0;
    const auto it = std::upper_bound(m_radius_table.begin(), m_radius_table.end(), radius_px);
    if (it == m_radius_table.end()) {
        const double r_max = m_radius_table.back();
        return m_camera.max_theta +
               (radius_px - r_max) / m_camera.radiusDerivative(m_camera.max_theta);
    }
    const size_t i = static_cast<size_t>(it - m_radius_table.begin());
    const double r0 = m_radius_table[i - 1], r1 = m_radius_table[i];
    double theta = (static_cast<double>(i - 1) + (radius_px - r0) / (r1 - r0)) * m_step;
    // Newton on r(θ) − r = 0
    for (int k = 0; k < 2; k++)
        theta -= (m_camera.radius(theta) - radius_px) / m_camera.radiusDerivative(theta);
    return theta;
}

Eigen::Vector2d PajdlaBaksteinInverse::unproject(const Eigen::Vector2d& uv) const
{
    // Eq. 1 solved for r cos φ and r sin φ
    const double x = uv.x() - m_camera.u0, y = uv.y() / m_camera.beta - m_camera.v0;
    return {std::atan2(y, x), thetaOfRadius(std::hypot(x, y))};
}

Eigen::Vector3d PajdlaBaksteinInverse::rayOfPixel(const Eigen::Vector2d& uv) const
{
    const Eigen::Vector2d a = unproject(uv);
    const double st = std::sin(a.y());
    return {st * std::cos(a.x()), st * std::sin(a.x()), std::cos(a.y())};
}

}  // namespace mrpt_vslam::sim
