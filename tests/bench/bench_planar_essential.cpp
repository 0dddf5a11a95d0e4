#include <benchmark/benchmark.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/UnifiedSphereCamera.h>
#include <mrpt_vslam/test/PlanarScene.h>
#include <mrpt_vslam/viewmap/PlanarEssentialRansac.h>

#include <cstdint>

using mrpt_vslam::viewmap::PlanarEssentialMatrix;
using mrpt_vslam::viewmap::PlanarEssentialRansac;
namespace scene_gen = mrpt_vslam::viewmap::test;

namespace {

struct TMatches {
    Eigen::Matrix3Xd rays_v, rays_l;
};

/** `n` matches of a random scene seen by the default 640 × 480 omni camera with 1 px of noise;
 *  the last `outlier_percent` % pair rays of different points. */
TMatches matches(int n, int outlier_percent)
{
    mrpt::random::CRandomGenerator rng(9);
    scene_gen::TSceneOptions opt;
    opt.points = size_t(n);
    const auto scene = scene_gen::randomScene(rng, opt);
    const mrpt_vslam::core::UnifiedSphereCamera camera;
    const int outliers = n * outlier_percent / 100;
    TMatches m{Eigen::Matrix3Xd(3, n), Eigen::Matrix3Xd(3, n)};
    for (int k = 0; k < n; k++) {
        const auto& p_l = scene.points[size_t(k < n - outliers ? k : (k + n / 2) % n)];
        m.rays_v.col(k) = *scene_gen::measuredRay(
            camera, scene_gen::rayFrom(scene.robot, scene.points[size_t(k)]), 1.0, rng);
        m.rays_l.col(k) =
            *scene_gen::measuredRay(camera, scene_gen::rayFrom(scene.view, p_l), 1.0, rng);
    }
    return m;
}

// One robust solve: arguments are the number of matches and the outlier percentage.
void BM_PlanarEssentialRansac(benchmark::State& state)
{
    const auto m = matches(int(state.range(0)), int(state.range(1)));
    const PlanarEssentialRansac ransac;
    mrpt::random::CRandomGenerator rng(1);
    size_t iterations = 0;
    for (auto _ : state) {
        const auto result = ransac.estimate(m.rays_v, m.rays_l, rng);
        iterations = result ? result->iterations : 0;
        benchmark::DoNotOptimize(result);
    }
    state.counters["samples"] = double(iterations);
}
BENCHMARK(BM_PlanarEssentialRansac)
    ->Args({100, 0})
    ->Args({100, 30})
    ->Args({150, 30})
    ->Args({200, 30})
    ->Args({200, 50})
    ->Unit(benchmark::kMicrosecond);

// The linear solve on all matches (what each refit costs).
void BM_PlanarEssentialFit(benchmark::State& state)
{
    const auto m = matches(int(state.range(0)), 0);
    for (auto _ : state) benchmark::DoNotOptimize(PlanarEssentialMatrix::fit(m.rays_v, m.rays_l));
}
BENCHMARK(BM_PlanarEssentialFit)->Arg(4)->Arg(100)->Arg(200)->Unit(benchmark::kMicrosecond);

}  // namespace
