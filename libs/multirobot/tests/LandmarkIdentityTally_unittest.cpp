#include <gtest/gtest.h>
#include <mrpt_vslam/multirobot/LandmarkIdentityTally.h>

#include <algorithm>

using namespace mrpt_vslam::multirobot;

// A history worked out by hand: a landmark's identity is that of the reading that created it,
// a later reading of another (known) identity is a wrong association, landmarks without an
// identity or no longer in the map do not count.
TEST(LandmarkIdentityTally, CountsAHandWorkedHistory)
{
    CVisualLandmarksMap map;
    TVisualLandmark lm;
    lm.times_seen = 1;
    const uint32_t a = map.addLandmark(lm, {}), b = map.addLandmark(lm, {}),
                   c = map.addLandmark(lm, {}), d = map.addLandmark(lm, {});
    const uint32_t removed = std::max({a, b, c, d}) + 1;  // not in the map
    const std::vector<TCorrespondence> history = {
        {0, a, 7},         // creates a: identity 7
        {0, b, 8},         // creates b: identity 8
        {1, a, 7},         // fused, same identity
        {1, a, 8},         // fused, another identity
        {0, c, 7},         // creates c: identity 7 again, its second landmark
        {0, d, -1},        // creates d without identity: d does not count
        {1, d, 8},         //   nor does what is fused into it
        {0, b, -1},        // fused into b, identity hidden: not a wrong association
        {0, removed, 9},   // a landmark the map no longer holds does not count
        {1, removed, 9}};  //
    const auto t = TLandmarkIdentityTally::of(history, map);
    EXPECT_EQ(t.landmarks_with_identity, 3u);            // a, b, c
    EXPECT_EQ(t.identities, 2u);                         // 7, 8
    EXPECT_EQ(t.identities_with_several_landmarks, 1u);  // 7: a and c
    EXPECT_EQ(t.fused_measurements, 3u);
    EXPECT_EQ(t.fused_with_another_identity, 1u);

    EXPECT_EQ(TLandmarkIdentityTally::of({}, map).landmarks_with_identity, 0u);
}

// A particle's history is its path's correspondences, oldest first.
TEST(LandmarkIdentityTally, HistoryOfAParticleIsOldestFirst)
{
    TTeamParticle p;
    const auto step = [](std::vector<TCorrespondence> correspondences) {
        TTeamStep s{TTeamPoses(1), {}};
        for (const auto& c : correspondences) s.correspondences.push_back(c);
        return s;
    };
    p.path.append(0.0, step({}));
    p.path.append(1.0, step({{0, 5, 1}, {0, 6, 2}}));
    p.path.append(2.0, step({{0, 5, 3}}));
    const auto h = TLandmarkIdentityTally::historyOf(p);
    ASSERT_EQ(h.size(), 3u);
    EXPECT_EQ(h[0].track_id, 1);
    EXPECT_EQ(h[1].track_id, 2);
    EXPECT_EQ(h[2].track_id, 3);
    EXPECT_TRUE(TLandmarkIdentityTally::historyOf(TTeamParticle()).empty());
}
