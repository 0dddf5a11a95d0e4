#include <benchmark/benchmark.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/GaussianProcessRegression.h>

#include <cmath>

using mrpt_vslam::core::GaussianProcessRegression;

namespace {

Eigen::MatrixXd points(int n, unsigned seed)
{
    mrpt::random::CRandomGenerator rng(seed);
    Eigen::MatrixXd X(n, 2);
    for (int i = 0; i < n; i++) X.row(i) << rng.drawUniform(0.0, 5.0), rng.drawUniform(0.0, 5.0);
    return X;
}

/// Smooth 2-D field plus N(0, 0.1²) noise.
Eigen::VectorXd targets(const Eigen::MatrixXd& X)
{
    mrpt::random::CRandomGenerator rng(3);
    Eigen::VectorXd y(X.rows());
    for (int i = 0; i < X.rows(); i++) {
        y[i] = std::sin(1.3 * X(i, 0)) * std::cos(0.9 * X(i, 1)) + rng.drawGaussian1D(0.0, 0.1);
    }
    return y;
}

// fit() + optimizeHyperParameters() with the default options (4 starting points), n in 2-D.
void BM_GpFitOptimize(benchmark::State& state)
{
    const Eigen::MatrixXd X = points(int(state.range(0)), 1);
    const Eigen::VectorXd y = targets(X);
    int iterations = 0;
    for (auto _ : state) {
        GaussianProcessRegression gp;
        gp.fit(X, y);
        iterations = gp.optimizeHyperParameters().iterations;
        benchmark::DoNotOptimize(gp.hyperParameters());
    }
    state.counters["bfgs_iterations"] = iterations;
}
BENCHMARK(BM_GpFitOptimize)->Arg(50)->Arg(200)->Arg(500)->Unit(benchmark::kMillisecond);

// fit() alone with fixed hyperparameters.
void BM_GpFit(benchmark::State& state)
{
    const Eigen::MatrixXd X = points(int(state.range(0)), 1);
    const Eigen::VectorXd y = targets(X);
    GaussianProcessRegression gp({0.8, 1.0, 0.1});
    for (auto _ : state) gp.fit(X, y);
}
BENCHMARK(BM_GpFit)->Arg(50)->Arg(200)->Arg(500)->Unit(benchmark::kMillisecond);

// Mean and variance at 1000 query points.
void BM_GpPredict1000(benchmark::State& state)
{
    const Eigen::MatrixXd X = points(int(state.range(0)), 1);
    GaussianProcessRegression gp({0.8, 1.0, 0.1});
    gp.fit(X, targets(X));
    const Eigen::MatrixXd Q = points(1000, 2);
    for (auto _ : state) benchmark::DoNotOptimize(gp.predict(Q));
    state.SetItemsProcessed(state.iterations() * 1000);
}
BENCHMARK(BM_GpPredict1000)->Arg(50)->Arg(200)->Arg(500)->Unit(benchmark::kMillisecond);

// Joint entropy of the predictive at 20 points.
void BM_GpJointEntropy20(benchmark::State& state)
{
    const Eigen::MatrixXd X = points(int(state.range(0)), 1);
    GaussianProcessRegression gp({0.8, 1.0, 0.1});
    gp.fit(X, targets(X));
    const Eigen::MatrixXd Q = points(20, 4);
    for (auto _ : state) benchmark::DoNotOptimize(gp.jointEntropy(Q));
}
BENCHMARK(BM_GpJointEntropy20)->Arg(50)->Arg(200)->Arg(500)->Unit(benchmark::kMicrosecond);

}  // namespace
