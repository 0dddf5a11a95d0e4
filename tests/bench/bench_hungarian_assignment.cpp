#include <benchmark/benchmark.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/HungarianAssignment.h>

#include <limits>

using mrpt_vslam::core::solveHungarianAssignment;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Square n×n matrix of uniform random costs.
void BM_HungarianSquare(benchmark::State& state)
{
    const auto n = static_cast<Eigen::Index>(state.range(0));
    mrpt::random::CRandomGenerator rng(1);
    Eigen::MatrixXd cost(n, n);
    for (Eigen::Index i = 0; i < n; i++) {
        for (Eigen::Index j = 0; j < n; j++) cost(i, j) = rng.drawUniform(0.0, 100.0);
    }
    for (auto _ : state) benchmark::DoNotOptimize(solveHungarianAssignment(cost));
    state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_HungarianSquare)
    ->Arg(10)
    ->Arg(30)
    ->Arg(100)
    ->Arg(300)
    ->Unit(benchmark::kMicrosecond)
    ->Complexity();

// Data association shape of Gamallo et al. 2013: N_z measurements × (N landmarks + N_z
// new-landmark columns). Costs are −log-likelihoods of gated pairs (others forbidden); column
// N + l holds the new-landmark cost of measurement l only. Args: N_z, N.
void BM_HungarianDataAssociation(benchmark::State& state)
{
    const auto n_z = static_cast<Eigen::Index>(state.range(0));
    const auto n_lm = static_cast<Eigen::Index>(state.range(1));
    mrpt::random::CRandomGenerator rng(2);
    Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(n_z, n_lm + n_z, kInf);
    for (Eigen::Index l = 0; l < n_z; l++) {
        for (Eigen::Index j = 0; j < n_lm; j++) {
            // Roughly 10 % of the pairs pass the gate.
            if (rng.drawUniform(0.0, 1.0) < 0.1) cost(l, j) = rng.drawUniform(0.0, 12.0);
        }
        cost(l, n_lm + l) = 9.0;
    }
    for (auto _ : state) benchmark::DoNotOptimize(solveHungarianAssignment(cost));
    state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_HungarianDataAssociation)
    ->Args({5, 50})
    ->Args({10, 100})
    ->Args({20, 200})
    ->Args({40, 400})
    ->Unit(benchmark::kMicrosecond)
    ->Complexity();

}  // namespace
