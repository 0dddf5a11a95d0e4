#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>

#include <vector>

namespace mrpt_vslam::sim {

/** Ground-truth path of a unicycle robot that follows a list of waypoints under speed limits.
 *
 *  1. Start at `start_{x,y,yaw}`, target the first waypoint.
 *  2. Every `control_dt`: heading error e to the target; ω = clamp(k_omega·e, ±max_omega);
 *     v = max_v·clamp(1 − |e|/slowdown_angle, 0, 1), also capped by k_v·distance on the last
 *     waypoint so the robot stops on it; integrate the unicycle exactly over control_dt.
 *  3. Switch to the next waypoint once closer than `switch_radius`.
 *  4. Sample the pose every `frame_period` (the camera rate).
 *
 *  No randomness: the path depends on the configuration only. */
class WaypointTrajectory : public mrpt::config::CLoadableOptions {
  public:
    /// @name Parameters (ini section [Trajectory]; angles in degrees with `_deg` keys)
    /// @{
    double start_x = 0, start_y = 0;              ///< [m] initial position
    double start_yaw = 0;                         ///< [rad] initial heading (ini: start_yaw_deg)
    std::vector<mrpt::math::TPoint2D> waypoints;  ///< [m] (ini: waypoints = x1 y1 x2 y2 ...)
    int frames = 320;                             ///< [-] number of frames of the full run
    double frame_period = 1.0;                    ///< [s] time between frames
    double max_v = 0.30;                          ///< [m/s] linear speed limit
    double max_omega = 0.52;      ///< [rad/s] angular speed limit (ini: max_omega_deg)
    double k_omega = 1.5;         ///< [1/s] heading-error gain
    double k_v = 0.5;             ///< [1/s] distance gain when stopping on the last waypoint
    double slowdown_angle = 1.0;  ///< [rad] heading error at which v drops to 0 (ini: _deg)
    double switch_radius = 0.4;   ///< [m] distance at which the next waypoint is targeted
    double control_dt = 0.02;     ///< [s] controller and integration step
    /// @}

    /// Robot poses at frames 0..frame_count-1 (t = k·frame_period).
    std::vector<mrpt::math::TPose2D> generate(int frame_count) const;

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                            const std::string& section) override;
};

}  // namespace mrpt_vslam::sim
