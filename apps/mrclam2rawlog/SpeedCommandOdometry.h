#pragma once

#include <mrpt/math/TPose2D.h>

#include <cstddef>
#include <vector>

#include "MrclamDataset.h"

namespace mrpt_vslam::mrclam {

/** Dead reckoning from speed commands: each command (v, w) holds from its time until the next
 *  one (the last one holds on), and each piece is integrated as an exact arc. The pose starts at
 *  (0, 0, 0) at the first command's time and stays there before it.
 *
 *  Queries must come in non-decreasing time (the integration goes forward once). */
class SpeedCommandOdometry {
  public:
    explicit SpeedCommandOdometry(const std::vector<TSpeedCommand>& commands);

    /// The odometry pose at time t [s] (t not before the previous query).
    mrpt::math::TPose2D poseAt(double t);
    /// The command holding at time t [s] (zero before the first one), after poseAt(t).
    TSpeedCommand commandAt(double t) const;

    /** The pose reached from `start` driving v [m/s], w [rad/s] for dt [s]:
     *  w ≠ 0: x += v/w (sin(θ + w dt) − sin θ), y −= v/w (cos(θ + w dt) − cos θ), θ += w dt;
     *  w = 0: x += v dt cos θ, y += v dt sin θ. The heading is wrapped to (−π, π]. */
    static mrpt::math::TPose2D arc(const mrpt::math::TPose2D& start, double v, double w, double dt);

  private:
    const std::vector<TSpeedCommand>& m_commands;
    size_t m_next = 0;           ///< first command not yet integrated up to its start
    mrpt::math::TPose2D m_pose;  ///< pose at the start of command m_next − 1
    double m_last_query = 0;
    bool m_queried = false;
};

}  // namespace mrpt_vslam::mrclam
