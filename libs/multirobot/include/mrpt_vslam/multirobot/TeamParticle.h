#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/multirobot/CVisualLandmarksMap.h>

#include <memory>
#include <vector>

namespace mrpt_vslam::multirobot {

/** The team's poses at one step of a particle's history; nodes are shared between the copies
 *  resampling makes, so a copy costs one pointer, not a path. */
struct TTeamPathNode {
    double timestamp = 0;                                   ///< [s]
    std::vector<mrpt::math::TPose2D> poses;                 ///< one per robot
    mutable std::shared_ptr<const TTeamPathNode> previous;  ///< mutable: see the destructor

    TTeamPathNode(double t, std::vector<mrpt::math::TPose2D> p,
                  std::shared_ptr<const TTeamPathNode> prev)
        : timestamp(t), poses(std::move(p)), previous(std::move(prev))
    {
    }
    /// Releases a chain of nodes nobody else holds iteratively (a long run would otherwise
    /// recurse once per step).
    ~TTeamPathNode();
};

/** One particle of the team filter (Gil et al. 2010, Eq. 5 and Table 1): the K robot poses, their
 *  paths and the map they share. */
struct TTeamParticle {
    std::vector<mrpt::math::TPose2D> poses;     ///< x_t,<1:K>
    std::shared_ptr<const TTeamPathNode> path;  ///< newest first
    CVisualLandmarksMap map;
    /// Σ_t log ω_t of Eq. 14, kept through resampling: the best particle has the largest.
    double accumulated_log_w = 0;
};

}  // namespace mrpt_vslam::multirobot
