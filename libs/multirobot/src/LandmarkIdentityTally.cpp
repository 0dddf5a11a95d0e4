#include <mrpt_vslam/multirobot/LandmarkIdentityTally.h>

#include <map>

namespace mrpt_vslam::multirobot {

TLandmarkIdentityTally TLandmarkIdentityTally::of(const std::vector<TCorrespondence>& history,
                                                  const CVisualLandmarksMap& map)
{
    TLandmarkIdentityTally t;
    std::map<uint32_t, int64_t> identityOf;  // of each landmark, from its first correspondence
    for (const TCorrespondence& c : history) {
        if (!map.landmark(c.landmark)) continue;
        const auto [it, created] = identityOf.emplace(c.landmark, c.track_id);
        if (created || it->second < 0) continue;
        t.fused_measurements++;
        if (c.track_id >= 0 && c.track_id != it->second) t.fused_with_another_identity++;
    }
    std::map<int64_t, size_t> landmarksOf;
    for (const auto& [landmark, identity] : identityOf)
        if (identity >= 0) landmarksOf[identity]++;
    for (const auto& [identity, n] : landmarksOf) {
        t.landmarks_with_identity += n;
        t.identities_with_several_landmarks += n > 1 ? 1 : 0;
    }
    t.identities = landmarksOf.size();
    return t;
}

std::vector<TCorrespondence> TLandmarkIdentityTally::historyOf(const TTeamParticle& p)
{
    std::vector<TCorrespondence> history;
    for (const auto* s : p.path.stepsOldestFirst())
        history.insert(history.end(), s->state.correspondences.begin(),
                       s->state.correspondences.end());
    return history;
}

}  // namespace mrpt_vslam::multirobot
