#include "ViconTrack.h"

#include <mrpt/math/wrap2pi.h>

#include <algorithm>

namespace mrpt_vslam::mrclam {

std::optional<mrpt::math::TPose2D> ViconTrack::poseAt(double t) const
{
    // first sample after t
    const auto after =
        std::upper_bound(m_samples.begin(), m_samples.end(), t,
                         [](double time, const TViconPose& s) { return time < s.t; });
    if (after == m_samples.begin()) return std::nullopt;
    const TViconPose& a = *(after - 1);
    if (a.t == t) return a.pose;
    if (after == m_samples.end() || after->t - a.t > m_max_gap) return std::nullopt;
    const TViconPose& b = *after;
    // p(t) = p_a + s (p_b − p_a), s = (t − t_a) / (t_b − t_a); heading along the shorter arc
    const double s = (t - a.t) / (b.t - a.t);
    return mrpt::math::TPose2D(
        a.pose.x + s * (b.pose.x - a.pose.x), a.pose.y + s * (b.pose.y - a.pose.y),
        mrpt::math::wrapToPi(a.pose.phi + s * mrpt::math::wrapToPi(b.pose.phi - a.pose.phi)));
}

}  // namespace mrpt_vslam::mrclam
