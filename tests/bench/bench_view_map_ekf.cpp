// One EKF step of view-based SLAM (Valiente et al. 2015): prediction, then one observation of a
// view (ViewMapEKF::update, Joseph form in O(n²)), with N views in the state (3 + 3N).
#include <benchmark/benchmark.h>
#include <mrpt_vslam/viewmap/ViewMapEKF.h>

#include <cmath>

namespace {

using mrpt_vslam::viewmap::ViewMapEKF;

void BM_ViewMapEKFStep(benchmark::State& state)
{
    const auto N = static_cast<size_t>(state.range(0));
    const Eigen::Matrix3d Q = Eigen::Vector3d(1e-4, 1e-4, 3e-5).asDiagonal();
    const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * 3e-4;
    // views on a circle of radius 3 m, the robot driving along it
    ViewMapEKF ekf({3, 0, M_PI / 2});
    const double step = 2 * M_PI / static_cast<double>(N);
    for (size_t i = 0; i < N; i++) {
        ekf.addView();
        ekf.predict({3 * step, 0, step}, Q);
    }
    size_t k = 0;
    for (auto _ : state) {
        ekf.predict({0.01, 0, 0.0033}, Q);
        const size_t view = (k++ * 7 + N / 2) % N;
        const auto h =
            mrpt_vslam::viewmap::predictViewObservation(ekf.robotPose(), ekf.viewPose(view));
        benchmark::DoNotOptimize(ekf.update(view, h, R, 9.21));
    }
}

}  // namespace

BENCHMARK(BM_ViewMapEKFStep)->Arg(10)->Arg(50)->Arg(200)->Unit(benchmark::kMicrosecond);
