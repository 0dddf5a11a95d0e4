#pragma once

#include <mrpt/containers/vector_with_small_size_optimization.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/core/ParticlePath.h>
#include <mrpt_vslam/multirobot/CVisualLandmarksMap.h>

#include <algorithm>
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

/** The team's poses, one per robot. Teams of up to 4 and steps of up to 8 correspondences are
 *  kept inline: every particle writes both each step, and resampling frees them by the
 *  thousand, so they go through no allocator. */
using TTeamPoses = mrpt::containers::vector_with_small_size_optimization<mrpt::math::TPose2D, 4>;
using TStepCorrespondences =
    mrpt::containers::vector_with_small_size_optimization<TCorrespondence, 8>;

/// `poses` as TTeamPoses.
inline TTeamPoses teamPoses(const std::vector<mrpt::math::TPose2D>& poses)
{
    TTeamPoses p(poses.size());
    std::copy(poses.begin(), poses.end(), p.begin());
    return p;
}

/** One step of a particle's history: the team's poses and the step's correspondences, robot by
 *  robot in the order they were fused. */
struct TTeamStep {
    TTeamPoses poses;  ///< one per robot
    TStepCorrespondences correspondences{};
};
using TTeamParticlePath = core::ParticlePath<TTeamStep>;

/** One particle of the team filter (Gil et al. 2010, Eq. 5 and Table 1): the K robot poses, their
 *  paths and the map they share. */
struct TTeamParticle {
    TTeamPoses poses;        ///< x_t,<1:K>
    TTeamParticlePath path;  ///< the team's steps, oldest first
    CVisualLandmarksMap map;
    /// Σ_t log ω_t of Eq. 14, kept through resampling: the best particle has the largest.
    double accumulated_log_w = 0;
    /// The correspondences of the step in progress, copied into the path when the step ends
    /// (resampling between robots copies them with the map they were fused into).
    TStepCorrespondences correspondences;
};

}  // namespace mrpt_vslam::multirobot
