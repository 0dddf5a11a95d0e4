#include <gtest/gtest.h>
#include <mrpt_vslam/multirobot/LandmarkDescriptorPool.h>

#include <algorithm>
#include <random>
#include <set>

using mrpt_vslam::multirobot::LandmarkDescriptorPool;
using mrpt_vslam::multirobot::TLandmarkCandidate;

namespace {
LandmarkDescriptorPool::TDescriptor randomDescriptor(std::mt19937& gen)
{
    std::normal_distribution<float> n;
    LandmarkDescriptorPool::TDescriptor d;
    float norm = 0;
    for (auto& v : d) {
        v = n(gen);
        norm += v * v;
    }
    for (auto& v : d) v /= std::sqrt(norm);
    return d;
}

/// 2000 landmarks in a box of ±10 x scale (z: a fifth), queried 200 times with radii
/// (0.3 + 0.4 k) x scale: the candidates equal a scan of every landmark, sorted by E.
void expectCandidatesOfABruteForceScan(double cell_size, double scale)
{
    std::mt19937 gen(5);
    std::uniform_real_distribution<double> u(-10 * scale, 10 * scale);
    LandmarkDescriptorPool pool(cell_size);
    // a few families of equal descriptors plus unique ones, so both E outcomes occur
    std::vector<LandmarkDescriptorPool::TDescriptor> families;
    for (int f = 0; f < 7; f++) families.push_back(randomDescriptor(gen));
    std::vector<LandmarkDescriptorPool::TDescriptor> ds;
    for (int i = 0; i < 2000; i++) {
        const auto d = i % 5 == 0 ? randomDescriptor(gen) : families[i % 7];
        ds.push_back(d);
        EXPECT_EQ(pool.add(d, {u(gen), u(gen), u(gen) / 5}), static_cast<uint32_t>(i));
    }
    size_t total = 0;
    for (int q = 0; q < 200; q++) {
        const Eigen::Vector3d c(u(gen), u(gen), u(gen) / 5);
        const double radius = (0.3 + (q % 10) * 0.4) * scale;
        const auto query = ds[q % ds.size()];
        const double max_E = (q % 3) * 0.5;
        std::vector<TLandmarkCandidate> got;
        pool.findCandidates(c, radius, query, max_E, got);
        std::vector<std::pair<float, uint32_t>> byE;
        for (uint32_t id = 0; id < pool.size(); id++) {
            const float E = LandmarkDescriptorPool::squaredDistance(query, pool.descriptor(id));
            if ((pool.creationPosition(id) - c).norm() <= radius && E <= max_E)
                byE.emplace_back(E, id);
        }
        std::sort(byE.begin(), byE.end());
        std::vector<uint32_t> expected;
        for (const auto& [E, id] : byE) expected.push_back(id);
        ASSERT_EQ(got.size(), expected.size()) << "query " << q;
        for (size_t i = 0; i < got.size(); i++) {
            EXPECT_EQ(got[i].id, expected[i]);
            EXPECT_FLOAT_EQ(got[i].E, LandmarkDescriptorPool::squaredDistance(
                                          query, pool.descriptor(got[i].id)));
        }
        total += got.size();
    }
    EXPECT_GT(total, 100u) << "the queries must find something for the comparison to mean much";
}
}  // namespace

TEST(LandmarkDescriptorPool, CandidatesEqualABruteForceScan)
{
    expectCandidatesOfABruteForceScan(0.7, 1);
}

// Radii of millions of cells (a tiny cell size) and coordinates beyond the keys' span of cells
// (far landmarks): the same candidates, found without walking every cell of the query box.
TEST(LandmarkDescriptorPool, CandidatesOfHugeQueryBoxesEqualABruteForceScan)
{
    expectCandidatesOfABruteForceScan(1e-6, 1);
    expectCandidatesOfABruteForceScan(1.0, 1e9);
}

TEST(LandmarkDescriptorPool, IdsAndErrors)
{
    std::mt19937 gen(1);
    LandmarkDescriptorPool pool;
    const auto d = randomDescriptor(gen);
    pool.addWithId(7, d, {1, 2, 3});
    EXPECT_TRUE(pool.contains(7));
    EXPECT_FALSE(pool.contains(3));
    EXPECT_EQ(pool.add(d, {0, 0, 0}), 8u);
    EXPECT_THROW(pool.addWithId(7, d, {0, 0, 0}), std::invalid_argument);
    EXPECT_THROW(pool.add(d, {NAN, 0, 0}), std::invalid_argument);
    EXPECT_THROW(LandmarkDescriptorPool(0.0), std::invalid_argument);
    EXPECT_FLOAT_EQ(LandmarkDescriptorPool::squaredDistance(d, d), 0.0f);
}

// Landmarks no map holds are taken out of the search, except those of identities; the
// candidates are then those of before among the kept ids, in the same order.
TEST(LandmarkDescriptorPool, ForgottenLandmarksAreNoLongerCandidates)
{
    std::mt19937 gen(9);
    std::uniform_real_distribution<double> u(-5, 5);
    LandmarkDescriptorPool pool(0.5);
    const auto d = randomDescriptor(gen);
    for (int i = 0; i < 300; i++) pool.add(d, {u(gen), u(gen), 0});
    pool.setLandmarkOfIdentity(42, 7);
    std::vector<uint32_t> held;
    for (uint32_t id = 0; id < 300; id++)
        if (id != 7 && gen() % 3 == 0) {  // 7: held by no map, kept by its identity
            held.resize(std::max<size_t>(held.size(), id / 32 + 1), 0);
            held[id / 32] |= 1u << (id % 32);
        }
    const auto isHeld = [&](uint32_t id) {
        return id / 32 < held.size() && (held[id / 32] >> (id % 32) & 1u);
    };
    std::vector<TLandmarkCandidate> before;
    pool.findCandidates({0, 0, 0}, 20, d, 0, before);
    ASSERT_EQ(before.size(), 300u);

    size_t kept = 0;
    for (uint32_t id = 0; id < 300; id++) kept += (isHeld(id) || id == 7) ? 1 : 0;
    EXPECT_EQ(pool.forgetAllBut(held), kept);
    std::vector<TLandmarkCandidate> after;
    pool.findCandidates({0, 0, 0}, 20, d, 0, after);
    std::vector<uint32_t> expected, got;
    for (const auto& c : before)
        if (isHeld(c.id) || c.id == 7) expected.push_back(c.id);
    for (const auto& c : after) got.push_back(c.id);
    EXPECT_EQ(got, expected);
    EXPECT_GT(expected.size(), 50u);
    EXPECT_LT(expected.size(), 150u);
    // forgetting is for the search only: descriptors and positions stay
    EXPECT_TRUE(pool.contains(0) && pool.contains(299));
    EXPECT_EQ(pool.descriptor(1), d);
}
