// One step of the multi-robot visual SLAM filter (Gil et al. 2010, Alg. 1 lines 5-15) on the
// synthetic team world, for the (M, B, K) of doc/multirobot.md: (500, 8, 2), (1500, 20, 2),
// (3000, 20, 3), the last also with resampling after each robot (R = 1, as office-team-3.ini);
// O = 0 the paper's proposal (pfStandardProposal), O = 1 pfOptimalProposal (office-team-2.ini);
// T threads (0: every core). Wall-clock time.
// The map is first built over 60 steps; the timed steps continue the run.
#include <benchmark/benchmark.h>
#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/multirobot/CMultiRobotVisualSLAM.h>
#include <mrpt_vslam/test/SyntheticTeamWorld.h>

namespace {
using namespace mrpt_vslam;
constexpr size_t kWarmUp = 60, kTimed = 100;

void BM_MultiRobotStep(benchmark::State& state)
{
    const auto M = static_cast<size_t>(state.range(0));
    const auto B = static_cast<unsigned>(state.range(1));
    const auto K = static_cast<size_t>(state.range(2));
    test::SyntheticTeamWorld::TParams wp;
    wp.robots = K;
    wp.landmarks = 1500;
    test::SyntheticTeamWorld world(wp);
    multirobot::CMultiRobotVisualSLAM filter(multirobot::CVisualLandmarksMap(), M, 1);
    filter.options.robots.clear();
    for (size_t k = 0; k < K; k++) filter.options.robots.push_back("R" + std::to_string(k + 1));
    filter.options.max_observations_per_robot = B;
    filter.options.resample_per_robot = state.range(3) != 0;
    filter.setThreadCount(static_cast<unsigned>(state.range(5)));
    filter.reset(world.startPoses(), world.time);
    mrpt::random::getRandomGenerator().randomize(1);
    mrpt::bayes::CParticleFilter pf;
    pf.m_options.PF_algorithm = state.range(4) != 0
                                    ? mrpt::bayes::CParticleFilter::pfOptimalProposal
                                    : mrpt::bayes::CParticleFilter::pfStandardProposal;
    pf.m_options.resamplingMethod = mrpt::bayes::CParticleFilter::prSystematic;
    pf.m_options.BETA = 0.5;
    pf.setVerbosityLevel(mrpt::system::LVL_ERROR);

    // pre-generated steps so that only the filter is timed
    std::vector<mrpt::obs::CActionCollection> acts(kWarmUp + kTimed);
    std::vector<mrpt::obs::CSensoryFrame> frames(kWarmUp + kTimed);
    for (size_t i = 0; i < acts.size(); i++) world.step(acts[i], frames[i]);
    size_t i = 0;
    for (; i < kWarmUp; i++) pf.executeOn(filter, &acts[i], &frames[i]);
    for (auto _ : state) {
        pf.executeOn(filter, &acts[i], &frames[i]);
        i++;
    }
    state.counters["landmarks"] = static_cast<double>(filter.bestParticle().map.size());
}
}  // namespace

BENCHMARK(BM_MultiRobotStep)
    ->ArgNames({"M", "B", "K", "R", "O", "T"})
    ->Args({500, 8, 2, 0, 0, 1})
    ->Args({500, 8, 2, 0, 1, 1})
    ->Args({1500, 20, 2, 0, 0, 1})
    ->Args({1500, 20, 2, 0, 1, 1})
    ->Args({3000, 20, 3, 0, 0, 1})
    ->Args({3000, 20, 3, 1, 0, 1})
    ->Args({3000, 20, 3, 0, 1, 1})
    ->Args({3000, 20, 3, 1, 1, 1})
    ->Args({3000, 20, 3, 1, 0, 0})
    ->Args({3000, 20, 3, 1, 1, 0})
    ->Iterations(kTimed)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
