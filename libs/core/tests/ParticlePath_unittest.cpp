#include <gtest/gtest.h>
#include <mrpt/bayes/CParticleFilterData.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/ParallelFor.h>
#include <mrpt_vslam/core/ParticleFilterDataImpl.h>
#include <mrpt_vslam/core/ParticlePath.h>

#include <algorithm>
#include <memory>
#include <vector>

using TPath = mrpt_vslam::core::ParticlePath<int>;

namespace {
/// `from` and `length` steps more, of states first, first + 1, ... at times 0.5 × state.
TPath extended(TPath from, int length, int first = 0)
{
    for (int i = first; i < first + length; i++) from.append(0.5 * i, i);
    return from;
}
std::vector<int> statesOf(const TPath& path)
{
    std::vector<int> states;
    for (const auto* s : path.stepsOldestFirst()) states.push_back(s->state);
    return states;
}
std::vector<int> range(int first, int length)
{
    std::vector<int> v(static_cast<size_t>(length));
    for (int i = 0; i < length; i++) v[static_cast<size_t>(i)] = first + i;
    return v;
}
}  // namespace

TEST(ParticlePath, StepsOldestFirstAcrossChunks)
{
    const int n = 3 * static_cast<int>(TPath::kChunk) + 2;
    const TPath path = extended(TPath(), n);
    ASSERT_EQ(path.size(), static_cast<size_t>(n));
    const auto steps = path.stepsOldestFirst();
    ASSERT_EQ(steps.size(), static_cast<size_t>(n));
    for (int i = 0; i < n; i++) {
        EXPECT_EQ(steps[static_cast<size_t>(i)]->state, i);
        EXPECT_DOUBLE_EQ(steps[static_cast<size_t>(i)]->timestamp, 0.5 * i);
    }
    EXPECT_EQ(path.newest().state, n - 1);
    std::vector<int> newest_first;
    path.forEachNewestFirst([&](const TPath::TStep& s) { newest_first.push_back(s.state); });
    const auto oldest_first = statesOf(path);
    EXPECT_EQ(newest_first, std::vector<int>(oldest_first.rbegin(), oldest_first.rend()));
    EXPECT_EQ(oldest_first, range(0, n));
    EXPECT_TRUE(TPath().stepsOldestFirst().empty());
    EXPECT_TRUE(TPath().empty());
}

TEST(ParticlePath, ReleasingAVeryLongPathDoesNotRecurse)
{
    // a recursive release of 250 000 chunks overflows the default 8 MB stack
    TPath path = extended(TPath(), 250000 * static_cast<int>(TPath::kChunk));
    path = TPath();
    SUCCEED();
}

// Copies share their history; each one's steps after the copy are its own, whichever of them
// took the shared chunk's free slots, and releasing one leaves the others whole.
TEST(ParticlePath, CopiesKeepTheirOwnStepsAndSurviveTheReleaseOfOthers)
{
    const TPath common = extended(TPath(), 100);
    TPath a = extended(common, 3, 1000), b = extended(common, 2, 2000);
    TPath c = extended(common, 10, 3000);
    auto expect = [](int own_first, int own) {
        auto v = range(0, 100);
        const auto o = range(own_first, own);
        v.insert(v.end(), o.begin(), o.end());
        return v;
    };
    EXPECT_EQ(statesOf(a), expect(1000, 3));
    EXPECT_EQ(statesOf(b), expect(2000, 2));
    a = TPath();  // releases a's own steps only
    EXPECT_EQ(statesOf(b), expect(2000, 2));
    EXPECT_EQ(statesOf(c), expect(3000, 10));
    EXPECT_EQ(statesOf(common), range(0, 100));
    const TPath d = extended(common, 1, 4000);  // the slot a took is not d's
    EXPECT_EQ(statesOf(d), expect(4000, 1));
}

// Resampling's copies add their steps on different threads at the same time.
TEST(ParticlePath, CopiesAddingStepsOnSeveralThreadsKeepTheirOwn)
{
    const TPath common = extended(TPath(), 5);
    std::vector<TPath> copies(64, common);
    for (int round = 0; round < 3; round++) {  // every copy shares its chunk with others
        mrpt_vslam::core::parallelFor(copies.size(), 4, [&](size_t i) {
            copies[i] = extended(copies[i], 11, 1000 * static_cast<int>(i) + 100 * round);
        });
        for (size_t i = 0; i < copies.size(); i += 2) copies[i + 1] = copies[i];
    }
    for (size_t i = 0; i < copies.size(); i++) {
        auto expected = range(0, 5);
        for (int round = 0; round < 3; round++) {
            // after each round the odd copies became their even neighbours
            const auto own = range(1000 * static_cast<int>(i - i % 2) + 100 * round, 11);
            expected.insert(expected.end(), own.begin(), own.end());
        }
        EXPECT_EQ(statesOf(copies[i]), expected) << i;
    }
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
    for (const size_t n : {1, 2, 17, 500, 3001}) {
        TFilter ours, theirs;
        ours.setThreadCount(n % 2 ? 3 : 1);
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
