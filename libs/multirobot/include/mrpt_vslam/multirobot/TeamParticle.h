#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/multirobot/CVisualLandmarksMap.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace mrpt_vslam::multirobot {

/** One fused measurement of a step, the correspondence c_t of FastSLAM: the robot that measured
 *  it, the landmark it updated or created, and its track_id (the identity the data gives it, if
 *  any; for the evaluation of the associations, TLandmarkIdentityTally). */
struct TCorrespondence {
    uint32_t robot = 0;
    uint32_t landmark = 0;
    int64_t track_id = -1;
};

/** The team's poses at one step of a particle's history; nodes are shared between the copies
 *  resampling makes, so a copy costs one pointer, not a path. */
struct TTeamPathNode {
    double timestamp = 0;                                   ///< [s]
    std::vector<mrpt::math::TPose2D> poses;                 ///< one per robot
    mutable std::shared_ptr<const TTeamPathNode> previous;  ///< mutable: see the destructor
    /// The step's correspondences, robot by robot in the order they were fused.
    std::vector<TCorrespondence> correspondences;

    TTeamPathNode(double t, std::vector<mrpt::math::TPose2D> p,
                  std::shared_ptr<const TTeamPathNode> prev, std::vector<TCorrespondence> c = {})
        : timestamp(t),
          poses(std::move(p)),
          previous(std::move(prev)),
          correspondences(std::move(c))
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
    /// The correspondences of the step in progress, moved into its path node when it ends
    /// (resampling between robots copies them with the map they were fused into).
    std::vector<TCorrespondence> correspondences;
};

}  // namespace mrpt_vslam::multirobot
