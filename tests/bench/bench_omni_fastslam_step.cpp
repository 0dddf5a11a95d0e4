// One FastSLAM 2.0 step (Alg. 1-4 for all particles, resampling included) on the shipped
// sports-hall bearings, for M ∈ {10, 100, 1000}. Each iteration processes the next frame; the
// filter restarts (untimed) after the last one.
#include <benchmark/benchmark.h>
#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/omni_fastslam/COmniFastSLAM.h>

#include <memory>

using namespace mrpt_vslam;

namespace {
const std::string kPrefix = std::string(MRPT_VSLAM_SOURCE_DIR) + "/datasets/sports-hall/hall";

struct TFrames {
    std::vector<std::pair<mrpt::obs::CActionCollection::Ptr, mrpt::obs::CSensoryFrame::Ptr>> pairs;
    mrpt::math::TPose2D start;
    TFrames()
    {
        core::RawlogReader reader(kPrefix + ".rawlog");
        for (core::TRawlogEntry e; reader.next(e);)
            if (e.actions && e.observations) pairs.emplace_back(e.actions, e.observations);
        const auto gt = core::TumTrajectory::load(kPrefix + ".groundtruth.tum");
        start = {gt.poses[0].x, gt.poses[0].y, gt.poses[0].yaw};
    }
};

const TFrames& frames()
{
    static const TFrames f;
    return f;
}

std::unique_ptr<omni_fastslam::COmniFastSLAM> newFilter(size_t M)
{
    omni_fastslam::CCeilingLightsMap map;
    map.sensorOptions.max_theta = 70 * M_PI / 180;
    map.insertionOptions.sigma0_xx = map.insertionOptions.sigma0_yy =
        map.insertionOptions.sigma0_zz = 0.1;
    map.insertionOptions.refine_initialization = true;
    auto f = std::make_unique<omni_fastslam::COmniFastSLAM>(map, M, 1);
    f->reset(frames().start, 0);
    return f;
}

void BM_OmniFastSLAMStep(benchmark::State& state)
{
    const auto M = static_cast<size_t>(state.range(0));
    const auto& data = frames();
    mrpt::random::getRandomGenerator().randomize(1);
    mrpt::bayes::CParticleFilter pf;
    pf.m_options.PF_algorithm = mrpt::bayes::CParticleFilter::pfOptimalProposal;
    pf.m_options.resamplingMethod = mrpt::bayes::CParticleFilter::prSystematic;
    pf.setVerbosityLevel(mrpt::system::LVL_ERROR);
    auto filter = newFilter(M);
    filter->setThreadCount(static_cast<unsigned>(state.range(1)));
    size_t k = 0;
    for (auto _ : state) {
        if (k == data.pairs.size()) {
            state.PauseTiming();
            filter = newFilter(M);
            filter->setThreadCount(static_cast<unsigned>(state.range(1)));
            k = 0;
            state.ResumeTiming();
        }
        pf.executeOn(*filter, data.pairs[k].first.get(), data.pairs[k].second.get());
        k++;
    }
    state.counters["landmarks"] =
        static_cast<double>(filter->bestParticle().map.landmarks().size());
}
// (M, threads): threads 0 = every core; wall-clock time
BENCHMARK(BM_OmniFastSLAMStep)
    ->ArgNames({"M", "T"})
    ->Args({10, 1})
    ->Args({100, 1})
    ->Args({1000, 1})
    ->Args({1000, 0})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
}  // namespace
