#include "SpeedCommandOdometry.h"

#include <mrpt/math/wrap2pi.h>

#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::mrclam {

SpeedCommandOdometry::SpeedCommandOdometry(const std::vector<TSpeedCommand>& commands)
    : m_commands(commands), m_pose(0, 0, 0)
{
}

mrpt::math::TPose2D SpeedCommandOdometry::arc(const mrpt::math::TPose2D& start, double v, double w,
                                              double dt)
{
    mrpt::math::TPose2D p = start;
    const double turn = w * dt;
    if (std::abs(turn) > 1e-12) {
        p.x += v / w * (std::sin(start.phi + turn) - std::sin(start.phi));
        p.y -= v / w * (std::cos(start.phi + turn) - std::cos(start.phi));
    } else {
        p.x += v * dt * std::cos(start.phi);
        p.y += v * dt * std::sin(start.phi);
    }
    p.phi = mrpt::math::wrapToPi(start.phi + turn);
    return p;
}

mrpt::math::TPose2D SpeedCommandOdometry::poseAt(double t)
{
    if (m_queried && t < m_last_query)
        throw std::logic_error("SpeedCommandOdometry: queries must go forward in time");
    m_queried = true;
    m_last_query = t;
    // Integrate every command that ended by t: command k holds on [t_k, t_{k+1}).
    while (m_next < m_commands.size() && m_commands[m_next].t <= t) {
        if (m_next > 0) {
            const TSpeedCommand& c = m_commands[m_next - 1];
            m_pose = arc(m_pose, c.v, c.w, m_commands[m_next].t - c.t);
        }
        m_next++;
    }
    if (m_next == 0) return {0, 0, 0};
    const TSpeedCommand& c = m_commands[m_next - 1];
    return arc(m_pose, c.v, c.w, t - c.t);
}

TSpeedCommand SpeedCommandOdometry::commandAt(double t) const
{
    size_t k = m_next;
    while (k > 0 && m_commands[k - 1].t > t) k--;
    if (k == 0) return {t, 0, 0};
    return m_commands[k - 1];
}

}  // namespace mrpt_vslam::mrclam
