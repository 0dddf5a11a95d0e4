#include <gtest/gtest.h>
#include <mrpt_vslam/multirobot/LandmarkStore.h>

#include <map>
#include <random>

using mrpt_vslam::multirobot::LandmarkStore;
using mrpt_vslam::multirobot::TVisualLandmark;

namespace {
TVisualLandmark landmark(double x)
{
    TVisualLandmark lm;
    lm.mean = {x, 2 * x, 3 * x};
    lm.cov = Eigen::Matrix3d::Identity() * x;
    lm.times_seen = 1;
    return lm;
}
}  // namespace

TEST(LandmarkStore, MatchesAStdMapUnderRandomInsertsUpdatesAndErases)
{
    std::mt19937 gen(3);
    LandmarkStore store;
    std::map<uint32_t, double> reference;
    for (int i = 0; i < 3000; i++) {
        const uint32_t id = gen() % 400;
        const double x = static_cast<double>(gen() % 1000);
        if (reference.count(id) && gen() % 5 == 0) {
            store.erase(id);
            reference.erase(id);
        } else if (reference.count(id) && gen() % 2) {
            store.modify(id).mean.x() = x;
            reference[id] = x;
        } else if (!reference.count(id)) {
            store.insert(id, landmark(x));
            reference[id] = x;
        }
    }
    ASSERT_EQ(store.size(), reference.size());
    for (uint32_t id = 0; id < 450; id++) {
        const auto* lm = store.find(id);
        ASSERT_EQ(lm != nullptr, reference.count(id) == 1) << id;
        if (lm) {
            EXPECT_EQ(lm->mean.x(), reference[id]);
        }
    }
    std::vector<uint32_t> ids;
    store.forEach([&](uint32_t id, const TVisualLandmark&) { ids.push_back(id); });
    std::vector<uint32_t> expected;
    for (const auto& [id, x] : reference) expected.push_back(id);
    EXPECT_EQ(ids, expected);

    // the bit set of held ids, ORed into one that holds other ids already
    std::vector<uint32_t> held{1u << 5};
    store.addIdsTo(held);
    for (uint32_t id = 0; id < 32 * held.size(); id++)
        EXPECT_EQ(held[id / 32] >> (id % 32) & 1u, (reference.count(id) || id == 5) ? 1u : 0u)
            << id;
    EXPECT_LE(held.size(), (450 + 31) / 32);
}

TEST(LandmarkStore, CopiesShareBlocksUntilOneIsWritten)
{
    LandmarkStore a;
    for (uint32_t id = 0; id < 10 * LandmarkStore::kBlockSize; id++) a.insert(id, landmark(id));
    EXPECT_EQ(a.unsharedBlocks(), 10u);

    LandmarkStore b = a;  // what resampling does
    EXPECT_EQ(a.unsharedBlocks(), 0u);
    EXPECT_EQ(b.unsharedBlocks(), 0u);

    b.modify(3).mean.x() = -1;  // block 0 only
    EXPECT_EQ(b.unsharedBlocks(), 1u);
    EXPECT_EQ(a.unsharedBlocks(), 1u);
    EXPECT_EQ(a.find(3)->mean.x(), 3.0) << "the copy's write must not reach the original";
    EXPECT_EQ(b.find(3)->mean.x(), -1.0);
    EXPECT_EQ(a.find(20)->mean.x(), 20.0);

    b.insert(1000, landmark(7));  // a new block of its own
    EXPECT_EQ(a.find(1000), nullptr);
    EXPECT_EQ(b.size(), a.size() + 1);
    b.clear();
    EXPECT_TRUE(b.empty());
    EXPECT_EQ(a.size(), 10u * LandmarkStore::kBlockSize);
}

TEST(LandmarkStore, AssignmentKeepsTheBlocksBothHold)
{
    constexpr uint32_t B = LandmarkStore::kBlockSize;
    LandmarkStore a;
    for (uint32_t id = 0; id < 4 * B; id++) a.insert(id, landmark(id));
    LandmarkStore b = a;
    b.modify(B + 3).mean.x() = -1;     // block 1 of b is its own
    b.insert(6 * B + 3, landmark(9));  // and block 6
    const TVisualLandmark* kept = a.find(3 * B + 1);
    ASSERT_NE(kept, nullptr);
    a = b;  // what resampling does into the data of a particle nobody drew
    EXPECT_EQ(a.find(3 * B + 1), kept) << "a block both held must stay where it was";
    EXPECT_EQ(a.size(), b.size());
    EXPECT_EQ(a.find(B + 3)->mean.x(), -1.0);
    EXPECT_EQ(a.find(6 * B + 3)->mean.x(), 9.0);
    EXPECT_EQ(a.unsharedBlocks(), 0u);

    LandmarkStore shorter;
    shorter.insert(3, landmark(3));
    a = shorter;
    EXPECT_EQ(a.size(), 1u);
    EXPECT_EQ(a.find(6 * B + 3), nullptr);
    EXPECT_EQ(a.find(B + 3), nullptr);
    a = a;  // NOLINT: self-assignment changes nothing
    EXPECT_EQ(a.find(3)->mean.x(), 3.0);
    EXPECT_EQ(b.find(B + 3)->mean.x(), -1.0) << "assigning to a must not change b";
}
