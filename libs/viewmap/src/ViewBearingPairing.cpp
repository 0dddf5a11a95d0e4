#include <mrpt_vslam/viewmap/ViewBearingPairing.h>

#include <cmath>

namespace mrpt_vslam::viewmap {

void ViewBearingPairing::add(const mrpt::math::TPose2D& u, const Eigen::Matrix3d& Q,
                             const COmniViewSLAM::TStepResult& step,
                             const mrpt::math::TPoint2D& camera)
{
    const size_t now = m_steps++;
    m_path += std::hypot(u.x, u.y);
    core::TOdometryGaussian motion;
    motion.mean = u;
    motion.cov = Q;
    m_motions.push_back(motion);
    for (auto it = m_open.begin(); it != m_open.end();)
        it = m_path - it->second.path > m_maxPath ? m_open.erase(it) : std::next(it);
    // the increments from the oldest open view's step on (m_motions[i] is step first + i's)
    const size_t oldest = m_open.empty() ? now : m_open.begin()->second.step;
    while (now + 1 - m_motions.size() < oldest) m_motions.pop_front();
    const size_t first = now + 1 - m_motions.size();

    for (const auto& o : step.observations) {
        const auto it = m_open.find(o.view);
        if (!o.estimated || it == m_open.end()) continue;
        const auto [uc, Qc] = core::composedOdometry(
            [&](size_t s) -> const core::TOdometryGaussian& { return m_motions[s - first]; },
            it->second.step, now);
        // a bearing needs the camera to have moved
        const mrpt::math::TPoint2D moved = uc.composePoint(camera);
        if (std::hypot(moved.x - camera.x, moved.y - camera.y) < 1e-3) continue;
        core::TEarlierPoseBearing& b = m_latest[o.view];
        b.sensor = {camera.x, camera.y};
        b.bearing = o.z.phi;
        b.var = o.R(0, 0);
        b.u = uc;
        b.Q = Qc;
    }
    if (step.new_view) m_open[*step.new_view] = {now, m_path};
}

std::vector<core::TEarlierPoseBearing> ViewBearingPairing::bearings() const
{
    std::vector<core::TEarlierPoseBearing> all;
    for (const auto& [view, b] : m_latest) all.push_back(b);
    return all;
}

}  // namespace mrpt_vslam::viewmap
