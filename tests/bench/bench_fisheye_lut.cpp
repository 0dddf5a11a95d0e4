#include <benchmark/benchmark.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/FisheyeLookupTable.h>

#include <algorithm>
#include <cmath>
#include <vector>

using mrpt_vslam::core::FisheyeLookupTable;
using mrpt_vslam::core::PajdlaBaksteinCamera;

namespace {

// Table build for the default camera (640×480) with the automatic steps; the counters give the
// table's memory and resolution: the largest θ half-range and on-sphere φ half-range
// (sin θ · φ half-range) over the valid pixels, excluding the centre pixel.
void BM_FisheyeLutBuild(benchmark::State& state)
{
    const PajdlaBaksteinCamera camera;
    for (auto _ : state) {
        FisheyeLookupTable lut(camera);
        benchmark::DoNotOptimize(lut.validPixelCount());
    }
    const FisheyeLookupTable lut(camera);
    double max_theta_half = 0, max_phi_half_on_sphere = 0;
    for (int row = 0; row < camera.height; row++) {
        for (int col = 0; col < camera.width; col++) {
            const auto& c = lut.cell(col, row);
            if (std::isnan(c.phi)) continue;
            max_theta_half = std::max(max_theta_half, double(c.theta_half_range));
            if (c.theta - c.theta_half_range <= 0) continue;  // pixel holding θ = 0
            max_phi_half_on_sphere =
                std::max(max_phi_half_on_sphere, std::sin(double(c.theta)) * c.phi_half_range);
        }
    }
    state.counters["bytes"] = static_cast<double>(lut.memoryBytes());
    state.counters["valid_px"] = static_cast<double>(lut.validPixelCount());
    state.counters["dphi_deg"] = mrpt::RAD2DEG(lut.deltaPhi());
    state.counters["dtheta_deg"] = mrpt::RAD2DEG(lut.deltaTheta());
    state.counters["max_theta_half_deg"] = mrpt::RAD2DEG(max_theta_half);
    state.counters["max_phi_half_sphere_deg"] = mrpt::RAD2DEG(max_phi_half_on_sphere);
}
BENCHMARK(BM_FisheyeLutBuild)->Unit(benchmark::kMillisecond);

// One look-up of a random sub-pixel centroid inside the image.
void BM_FisheyeLutLookup(benchmark::State& state)
{
    const FisheyeLookupTable lut{PajdlaBaksteinCamera()};
    mrpt::random::CRandomGenerator rng(3);
    std::vector<Eigen::Vector2d> queries(4096);
    for (auto& q : queries) q = {rng.drawUniform(0.0, 639.0), rng.drawUniform(0.0, 479.0)};
    size_t i = 0;
    for (auto _ : state) {
        const Eigen::Vector2d& q = queries[i++ & 4095];
        benchmark::DoNotOptimize(lut.lookup(q.x(), q.y()));
    }
    state.counters["bytes"] = static_cast<double>(lut.memoryBytes());
}
BENCHMARK(BM_FisheyeLutLookup);

}  // namespace
