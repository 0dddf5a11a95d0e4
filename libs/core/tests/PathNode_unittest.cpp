#include <gtest/gtest.h>
#include <mrpt/bayes/CParticleFilterData.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/ParticleFilterDataImpl.h>
#include <mrpt_vslam/core/PathNode.h>

#include <algorithm>
#include <memory>
#include <vector>

using mrpt_vslam::core::nodesOldestFirst;
using TNode = mrpt_vslam::core::TPathNode<int>;

namespace {
std::shared_ptr<const TNode> chain(int length, std::shared_ptr<const TNode> from = nullptr)
{
    for (int i = 0; i < length; i++)
        from = std::make_shared<const TNode>(0.5 * i, std::move(from), i);
    return from;
}
}  // namespace

TEST(PathNode, NodesOldestFirst)
{
    const auto path = chain(5);
    const auto nodes = nodesOldestFirst(path.get());
    ASSERT_EQ(nodes.size(), 5u);
    for (int i = 0; i < 5; i++) {
        EXPECT_EQ(nodes[i]->state, i);
        EXPECT_DOUBLE_EQ(nodes[i]->timestamp, 0.5 * i);
    }
    EXPECT_TRUE(nodesOldestFirst<int>(nullptr).empty());
}

TEST(PathNode, ReleasingAVeryLongChainDoesNotRecurse)
{
    // a recursive release of 10^6 nodes overflows the default 8 MB stack
    auto path = chain(1000000);
    path.reset();
    SUCCEED();
}

TEST(PathNode, SharedHistorySurvivesTheBranchThatIsReleased)
{
    const auto common = chain(100);
    auto a = chain(3, common), b = chain(2, common);
    a.reset();  // releases a's own 3 nodes only
    EXPECT_EQ(nodesOldestFirst(b.get()).size(), 102u);
    EXPECT_EQ(nodesOldestFirst(common.get()).size(), 100u);
}

namespace {
struct TWeighted {
    double accumulated_log_w = 0;
};
using TBase =
    mrpt::bayes::CParticleFilterData<TWeighted, mrpt::bayes::particle_storage_mode::POINTER>;
struct TFilter : public TBase,
                 public mrpt_vslam::core::ParticleFilterDataImpl<TFilter, TBase::CParticleList> {};
}  // namespace

TEST(ParticleFilterDataImpl, BestParticleHasTheLargestAccumulatedLogWeight)
{
    TFilter f;
    f.m_particles.resize(4);
    for (auto& p : f.m_particles) p.d.reset(new TWeighted);
    const std::vector<double> steps{-1.0, -0.2, -3.0, -0.2};
    for (size_t i = 0; i < 4; i++) {
        TFilter::addLogWeight(f.m_particles[i], steps[i]);
        TFilter::addLogWeight(f.m_particles[i], -0.5);
    }
    EXPECT_DOUBLE_EQ(f.m_particles[2].log_w, -3.5);
    EXPECT_DOUBLE_EQ(f.m_particles[2].d->accumulated_log_w, -3.5);
    // the first of the two equal ones
    EXPECT_EQ(&f.bestParticle(), f.m_particles[1].d.get());
    // resampling resets the weights, not the accumulated sums
    f.performSubstitution({2, 2, 0, 1});
    for (const auto& p : f.m_particles) EXPECT_EQ(p.log_w, 0);
    EXPECT_DOUBLE_EQ(f.bestParticle().accumulated_log_w, -0.7);
}

// ESS() and normalizeWeights() are MRPT's, without its dynamic_cast per particle: the same
// values bit for bit on random weights.
TEST(ParticleFilterDataImpl, EssAndNormalizationAreMrpts)
{
    using TMrpt = mrpt::bayes::CParticleFilterDataImpl<TFilter, TBase::CParticleList>;
    mrpt::random::CRandomGenerator rng(7);
    for (const size_t n : {1, 2, 17, 500}) {
        TFilter ours, theirs;
        for (TFilter* f : {&ours, &theirs}) f->m_particles.resize(n);
        for (size_t i = 0; i < n; i++) {
            ours.m_particles[i].log_w = theirs.m_particles[i].log_w = rng.drawUniform(-30.0, 5.0);
            for (TFilter* f : {&ours, &theirs}) f->m_particles[i].d.reset(new TWeighted);
        }
        EXPECT_EQ(ours.ESS(), theirs.TMrpt::ESS()) << n;
        double our_max = 0, their_max = 0;
        EXPECT_EQ(ours.normalizeWeights(&our_max), theirs.TMrpt::normalizeWeights(&their_max));
        EXPECT_EQ(our_max, their_max);
        for (size_t i = 0; i < n; i++)
            EXPECT_EQ(ours.m_particles[i].log_w, theirs.m_particles[i].log_w);
        EXPECT_EQ(ours.ESS(), theirs.TMrpt::ESS()) << n;
    }
    EXPECT_EQ(TFilter().normalizeWeights(), 0);
}

// Resampling gives MRPT's set (the same data in the same order) and reuses the data of the
// particles nobody drew for the copies: no particle data is allocated when the count stays.
TEST(ParticleFilterDataImpl, SubstitutionIsMrptsAndReusesTheDroppedParticles)
{
    using TMrpt = mrpt::bayes::CParticleFilterDataImpl<TFilter, TBase::CParticleList>;
    mrpt::random::CRandomGenerator rng(11);
    for (const size_t n : {1, 2, 9, 300}) {
        for (const size_t m : {n, n + 3, n / 2 + 1}) {  // as many, more and fewer drawn
            TFilter ours, theirs;
            std::vector<const TWeighted*> before;
            for (TFilter* f : {&ours, &theirs}) {
                f->m_particles.resize(n);
                for (size_t i = 0; i < n; i++) {
                    f->m_particles[i].d.reset(new TWeighted{static_cast<double>(i)});
                    f->m_particles[i].log_w = -1;
                }
            }
            for (const auto& p : ours.m_particles) before.push_back(p.d.get());
            std::vector<size_t> indx(m);
            for (auto& i : indx) i = rng.drawUniform32bit() % n;
            ours.performSubstitution(indx);
            theirs.TMrpt::performSubstitution(indx);
            ASSERT_EQ(ours.m_particles.size(), m);
            ASSERT_EQ(theirs.m_particles.size(), m);
            size_t reused = 0;
            for (size_t i = 0; i < m; i++) {
                EXPECT_EQ(ours.m_particles[i].d->accumulated_log_w,
                          theirs.m_particles[i].d->accumulated_log_w)
                    << n << " " << m << " " << i;
                EXPECT_EQ(ours.m_particles[i].log_w, 0);
                reused += std::count(before.begin(), before.end(), ours.m_particles[i].d.get());
            }
            EXPECT_EQ(reused, std::min(n, m)) << n << " " << m;
        }
    }
}
