#pragma once

#include <mrpt_vslam/multirobot/CVisualLandmarksMap.h>
#include <mrpt_vslam/multirobot/TeamParticle.h>

#include <cstddef>
#include <vector>

namespace mrpt_vslam::multirobot {

/** How the associations went where measurements carry identities (range-bearing data imported
 *  with kept ids, front-end tracks: TLandmarkMeasurement::track_id ≥ 0), from the
 *  correspondences a map was made with; evaluation only, no filter reads identities this way.
 *  A landmark's identity is the track_id of the measurement that created it (its first
 *  correspondence); only landmarks with one (≥ 0) that the map holds count. */
struct TLandmarkIdentityTally {
    size_t landmarks_with_identity = 0;
    size_t identities = 0;                         ///< distinct identities of those landmarks
    size_t identities_with_several_landmarks = 0;  ///< duplicated landmarks
    size_t fused_measurements = 0;                 ///< into those landmarks, after their first
    /// of those, the ones with an identity (≥ 0) other than the landmark's: wrong associations
    size_t fused_with_another_identity = 0;

    /** The tally of `history` (c_1..c_t, oldest first: a particle's, historyOf(), or those
     *  TeamPathSmoother made its map with) over the landmarks of `map`. */
    static TLandmarkIdentityTally of(const std::vector<TCorrespondence>& history,
                                     const CVisualLandmarksMap& map);
    /// A particle's correspondences, from its path, oldest first.
    static std::vector<TCorrespondence> historyOf(const TTeamParticle& p);
};

}  // namespace mrpt_vslam::multirobot
