// The omni front-end of the view SLAM (Valiente et al. 2015) on rendered 640 × 480 images of the
// omni-views world: feature extraction, matching (restricted to the predicted area or not), the
// whole observation (matching, RANSAC, refinement and R), and one step: the current image's
// features and the observations of 2 candidate views. Budget of a whole step: 50 ms on one core.
#include <benchmark/benchmark.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/sim/OmniViewsScenario.h>
#include <mrpt_vslam/viewmap/OmniFeatureExtractor.h>
#include <mrpt_vslam/viewmap/OmniViewObserver.h>

#include <array>
#include <vector>

using mrpt_vslam::viewmap::OmniFeatureExtractor;
using mrpt_vslam::viewmap::OmniViewObserver;
using mrpt_vslam::viewmap::TPrediction;
using mrpt_vslam::viewmap::TViewFeatures;

namespace {

/// The current image and two stored views 0.8 and 1.2 m away with other headings, their
/// features, and predictions off the truth by 1σ (σ = 3° in φ, 1.5° in β).
struct TSetup {
    mrpt::img::CImage current_image;
    TViewFeatures current;
    std::array<TViewFeatures, 2> views;
    std::array<TPrediction, 2> predictions;
    OmniFeatureExtractor extractor;

    static TSetup& get()
    {
        static TSetup s = make();
        return s;
    }

  private:
    static TSetup make()
    {
        mrpt_vslam::sim::OmniViewsScenario sc;
        sc.loadConfig(mrpt::config::CConfigFile(
            MRPT_VSLAM_SOURCE_DIR "/share/mrpt-vslam/config/vslam-sim/omni-views.ini"));
        const auto model = sc.world.build(sc.textures);
        sc.renderer.reset(7);
        const auto render = [&](const mrpt::math::TPose2D& pose) {
            return sc.renderer.render(
                model.scene, mrpt::poses::CPose3D(mrpt::poses::CPose2D(pose)) + sc.camera_on_robot);
        };
        // In the corridor (y 4..6) and at the door of room B.
        const mrpt::math::TPose2D robot{4.0, 5.0, 0.4};
        const std::array<mrpt::math::TPose2D, 2> view_poses{mrpt::math::TPose2D{4.8, 5.1, 2.5},
                                                            mrpt::math::TPose2D{2.9, 4.6, -1.2}};
        const OmniFeatureExtractor fx(sc.renderer.camera(), Eigen::Matrix3d::Identity(), {});
        TSetup s{render(robot), {}, {}, {}, fx};
        s.current = fx.extract(s.current_image);
        for (size_t v = 0; v < 2; v++) {
            s.views[v] = fx.extract(render(view_poses[v]));
            const auto truth = mrpt_vslam::viewmap::predictViewObservation(robot, view_poses[v]);
            s.predictions[v].z = {truth.phi + mrpt::DEG2RAD(3.0), truth.beta - mrpt::DEG2RAD(1.5)};
            s.predictions[v].S << std::pow(mrpt::DEG2RAD(3.0), 2), 0, 0,
                std::pow(mrpt::DEG2RAD(1.5), 2);
        }
        return s;
    }
};

OmniViewObserver observer(bool restrict_search_area)
{
    OmniViewObserver::TOptions opt;
    opt.matching.restrict_search_area = restrict_search_area;
    return OmniViewObserver(opt);
}

// Fast-Hessian, oriented SURF descriptors and rays of one image, on T threads (0: every core).
void BM_ExtractFeatures(benchmark::State& state)
{
    TSetup& s = TSetup::get();
    OmniFeatureExtractor extractor = s.extractor;
    extractor.setThreadCount(static_cast<unsigned>(state.range(0)));
    size_t n = 0;
    for (auto _ : state) {
        const TViewFeatures f = extractor.extract(s.current_image);
        n = f.size();
        benchmark::DoNotOptimize(f);
    }
    state.counters["features"] = double(n);
}
BENCHMARK(BM_ExtractFeatures)
    ->ArgName("T")
    ->Arg(1)
    ->Arg(0)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Matching of the current image with view 0; argument 1: restricted to the predicted area.
void BM_MatchView(benchmark::State& state)
{
    TSetup& s = TSetup::get();
    const OmniViewObserver obs = observer(state.range(0) != 0);
    size_t matches = 0, compared = 0;
    for (auto _ : state) {
        const auto m = obs.match(s.current, s.views[0], s.predictions[0]);
        matches = m.matches.size();
        compared = m.candidates_compared;
        benchmark::DoNotOptimize(m);
    }
    state.counters["matches"] = double(matches);
    state.counters["compared"] = double(compared);
}
BENCHMARK(BM_MatchView)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

// Matching, RANSAC, refinement and R for view 0; argument 1: restricted to the predicted area.
void BM_ObserveView(benchmark::State& state)
{
    TSetup& s = TSetup::get();
    const OmniViewObserver obs = observer(state.range(0) != 0);
    mrpt::random::CRandomGenerator rng(1);
    size_t inliers = 0, matches = 0;
    for (auto _ : state) {
        const auto o = obs.observe(s.current, s.views[0], s.predictions[0], rng);
        inliers = o ? o->inliers : 0;
        matches = o ? o->matches : 0;
        benchmark::DoNotOptimize(o);
    }
    state.counters["inliers"] = double(inliers);
    state.counters["matches"] = double(matches);
}
BENCHMARK(BM_ObserveView)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

// One step of the front-end: the current image's features and the observations of 2 candidate
// views (restricted matching, the defaults).
void BM_FrontEndStep(benchmark::State& state)
{
    TSetup& s = TSetup::get();
    const OmniViewObserver obs = observer(true);
    mrpt::random::CRandomGenerator rng(1);
    size_t observed = 0;
    for (auto _ : state) {
        const TViewFeatures current = s.extractor.extract(s.current_image);
        observed = 0;
        for (size_t v = 0; v < 2; v++) {
            const auto o = obs.observe(current, s.views[v], s.predictions[v], rng);
            observed += o.has_value();
            benchmark::DoNotOptimize(o);
        }
    }
    state.counters["observed"] = double(observed);
}
BENCHMARK(BM_FrontEndStep)->Unit(benchmark::kMillisecond);

}  // namespace
