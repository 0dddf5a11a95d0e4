#include <mrpt/core/bits_math.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/core/TextColumns.h>
#include <mrpt_vslam/sim/ConfigReading.h>
#include <mrpt_vslam/sim/WaypointTrajectory.h>

#include <algorithm>
#include <cmath>

namespace mrpt_vslam::sim {

std::vector<mrpt::math::TPose2D> WaypointTrajectory::generate(int frame_count) const
{
    std::vector<mrpt::math::TPose2D> out;
    out.reserve(static_cast<size_t>(std::max(frame_count, 0)));
    mrpt::math::TPose2D pose(start_x, start_y, start_yaw);
    size_t target = 0;
    const int substeps = std::max(1, static_cast<int>(std::lround(frame_period / control_dt)));
    const double dt = frame_period / substeps;

    for (int k = 0; k < frame_count; k++) {
        out.push_back(pose);
        for (int s = 0; s < substeps; s++) {
            while (target + 1 < waypoints.size() &&
                   std::hypot(waypoints[target].x - pose.x, waypoints[target].y - pose.y) <
                       switch_radius)
                target++;
            if (target >= waypoints.size()) break;
            const double dx = waypoints[target].x - pose.x, dy = waypoints[target].y - pose.y;
            const double dist = std::hypot(dx, dy);
            const double e = mrpt::math::wrapToPi(std::atan2(dy, dx) - pose.phi);
            const double w = std::clamp(k_omega * e, -max_omega, max_omega);
            double v = max_v * std::clamp(1.0 - std::abs(e) / slowdown_angle, 0.0, 1.0);
            if (target + 1 == waypoints.size()) v = std::min(v, k_v * dist);
            // Exact unicycle integration over dt (arc of radius v/ω); for tiny ω the chord
            // at the mid heading, which avoids the cancellation in the arc formula.
            const double phi1 = pose.phi + w * dt;
            if (std::abs(w) > 1e-3) {
                pose.x += v / w * (std::sin(phi1) - std::sin(pose.phi));
                pose.y -= v / w * (std::cos(phi1) - std::cos(pose.phi));
            } else {
                pose.x += v * dt * std::cos(pose.phi + 0.5 * w * dt);
                pose.y += v * dt * std::sin(pose.phi + 0.5 * w * dt);
            }
            pose.phi = mrpt::math::wrapToPi(phi1);
        }
    }
    return out;
}

void WaypointTrajectory::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                            const std::string& s)
{
    MRPT_LOAD_CONFIG_VAR(start_x, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(start_y, double, cfg, s);
    start_yaw = readDegrees(cfg, s, "start_yaw_deg", start_yaw);
    MRPT_LOAD_CONFIG_VAR(frames, int, cfg, s);
    MRPT_LOAD_CONFIG_VAR(frame_period, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(max_v, double, cfg, s);
    max_omega = readDegrees(cfg, s, "max_omega_deg", max_omega);
    MRPT_LOAD_CONFIG_VAR(k_omega, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(k_v, double, cfg, s);
    slowdown_angle = readDegrees(cfg, s, "slowdown_angle_deg", slowdown_angle);
    MRPT_LOAD_CONFIG_VAR(switch_radius, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(control_dt, double, cfg, s);

    std::vector<double> xy;
    for (const auto& p : waypoints) {
        xy.push_back(p.x);
        xy.push_back(p.y);
    }
    xy = core::readNumberList(cfg, s, "waypoints", xy);
    checkConfig(!xy.empty() && xy.size() % 2 == 0, s, "waypoints", "a non-empty list of x y pairs");
    waypoints.clear();
    for (size_t i = 0; i < xy.size(); i += 2) waypoints.emplace_back(xy[i], xy[i + 1]);

    checkConfig(frames > 0, s, "frames", "> 0");
    checkConfig(frame_period > 0, s, "frame_period", "> 0");
    checkConfig(max_v > 0, s, "max_v", "> 0");
    checkConfig(max_omega > 0, s, "max_omega_deg", "> 0");
    checkConfig(k_omega > 0 && k_v > 0, s, "k_omega, k_v", "> 0");
    checkConfig(slowdown_angle > 0, s, "slowdown_angle_deg", "> 0");
    checkConfig(switch_radius > 0, s, "switch_radius", "> 0");
    checkConfig(control_dt > 0 && control_dt <= frame_period, s, "control_dt",
                "in (0, frame_period]");
}

}  // namespace mrpt_vslam::sim
