// view-slam: one whole filter step (features + matching + RANSAC + EKF updates + view decision)
// on the shipped omni-views frames with the shipped config, each policy; and the information
// policy's decision alone (GP fit, hyperparameters, hypothetical updates). Each step iteration
// processes the next frame; the filter restarts (untimed) after the last one.
#include <benchmark/benchmark.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/viewmap/COmniViewSLAM.h>

#include <memory>

using namespace mrpt_vslam;

namespace {
const std::string kPrefix = std::string(MRPT_VSLAM_SOURCE_DIR) + "/datasets/omni-views/rooms";
const std::string kConfig =
    std::string(MRPT_VSLAM_SOURCE_DIR) + "/share/mrpt-vslam/config/view-slam/omni-views.ini";

/// The shipped frames in memory: odometry increment, its covariance and the image.
struct TFrames {
    struct TFrame {
        mrpt::math::TPose2D u;
        Eigen::Matrix3d Q;
        mrpt::img::CImage image;
    };
    std::vector<TFrame> frames;
    mrpt::math::TPose2D start;
    TFrames()
    {
        core::RawlogReader reader(kPrefix + ".rawlog");
        for (core::TRawlogEntry e; reader.next(e);) {
            if (!e.actions || !e.observations) continue;
            const auto img =
                e.observations->getObservationBySensorLabelAs<mrpt::obs::CObservationImage::Ptr>(
                    "OMNICAM");
            const auto [Q, u] =
                e.actions->getBestMovementEstimation()->poseChange->getCovarianceAndMean();
            TFrame f{u.asTPose(), Q.asEigen(), {}};
            img->image.getWidth();  // loads the external file
            f.image = img->image.makeDeepCopy();
            frames.push_back(std::move(f));
        }
        const auto gt = core::TumTrajectory::load(kPrefix + ".groundtruth.tum");
        start = {gt.poses[0].x, gt.poses[0].y, gt.poses[0].yaw};
    }
};

const TFrames& data()
{
    static const TFrames f;
    return f;
}

std::unique_ptr<viewmap::COmniViewSLAM> newSLAM(const std::string& policy)
{
    core::CheckedConfigFile cfg;
    cfg.loadFile(kConfig, {{"ViewInitialization", "policy", policy}});
    return viewmap::COmniViewSLAM::fromConfig(cfg, 1);
}

void runSteps(benchmark::State& state, const std::string& policy)
{
    const auto& d = data();
    auto slam = newSLAM(policy);
    slam->reset(d.start);
    size_t k = 0, views = 0;
    for (auto _ : state) {
        if (k == d.frames.size()) {
            state.PauseTiming();
            views += slam->ekf().viewCount();
            slam->reset(d.start);
            k = 0;
            state.ResumeTiming();
        }
        const auto& f = d.frames[k++];
        benchmark::DoNotOptimize(slam->processStep(f.u, f.Q, &f.image, double(k)));
    }
    state.counters["views_at_end"] = double(slam->ekf().viewCount());
}

void BM_ViewSLAMStepTraditional(benchmark::State& state) { runSteps(state, "traditional"); }
void BM_ViewSLAMStepInformation(benchmark::State& state) { runSteps(state, "information"); }

/// The information policy's decision at the end of a step: 15 views, 3 of them observed, the
/// features of a real frame with half of them consistent.
void BM_InformationPolicyDecision(benchmark::State& state)
{
    const auto& d = data();
    auto slam = newSLAM("information");
    slam->reset(d.start);
    for (size_t k = 0; k < d.frames.size(); k++)
        slam->processStep(d.frames[k].u, d.frames[k].Q, &d.frames[k].image, double(k));
    viewmap::ViewMapEKF ekf = slam->ekf();
    while (ekf.viewCount() < 15) {
        ekf.predict({0.3, 0, 0.1}, Eigen::Matrix3d::Identity() * 1e-4);
        ekf.addView();
    }
    ekf.predict({0.2, 0, 0}, Eigen::Matrix3d::Identity() * 1e-4);
    const auto& features = slam->map().views().back().features;
    viewmap::TViewPolicyInputs in;
    in.ekf = &ekf;
    in.features = &features;
    for (size_t k = 0; k < features.size(); k++) in.consistent.push_back(k % 2 == 0);
    for (size_t v = 12; v < 15; v++)
        in.observed.push_back({v, Eigen::Matrix2d::Identity() * 1e-4, 60});
    in.nearest_view_distance = 0.5;
    in.P_vv_previous = ekf.robotCovariance() * 0.9;
    in.P_vv_predicted = ekf.robotCovariance();
    viewmap::ViewInitializationPolicy::TOptions options;
    options.existence.refit_every = int(state.range(0));
    auto policy = viewmap::ViewInitializationPolicy::create(options);
    mrpt::random::CRandomGenerator rng(1);
    policy->decide(in, rng);  // the first fit starts the hyperparameters from scratch, once a run
    for (auto _ : state) benchmark::DoNotOptimize(policy->decide(in, rng));
    state.counters["features"] = double(features.size());
}

}  // namespace

BENCHMARK(BM_ViewSLAMStepTraditional)->Unit(benchmark::kMillisecond)->Iterations(80);
BENCHMARK(BM_ViewSLAMStepInformation)->Unit(benchmark::kMillisecond)->Iterations(80);
// Hyperparameters refitted every frame (1) and every 10 frames (the shipped config), after a first
// decision; a fixed 20 decisions, so that the mean holds the refits in their shipped proportion.
BENCHMARK(BM_InformationPolicyDecision)
    ->Arg(1)
    ->Arg(10)
    ->Iterations(20)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
