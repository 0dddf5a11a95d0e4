#include <benchmark/benchmark.h>
#include <mrpt/img/CImage.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/FastHessianDetector.h>
#include <mrpt_vslam/core/USurfDescriptor.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

using mrpt_vslam::core::FastHessianDetector;
using mrpt_vslam::core::IntegralImage;
using mrpt_vslam::core::USurfDescriptor;

namespace {

constexpr int kWidth = 640, kHeight = 480;

/// Deterministic 640 × 480 scene: random flat rectangles under random Gaussian blobs, so that
/// the detector meets both corners/edges and blobs at many scales.
mrpt::img::CImage scene()
{
    mrpt::random::CRandomGenerator rng(4);
    std::vector<double> px(size_t(kWidth) * kHeight, 110.0);
    for (int k = 0; k < 600; k++) {
        const int c0 = int(rng.drawUniform(0.0, kWidth)), r0 = int(rng.drawUniform(0.0, kHeight));
        const int c1 = std::min(kWidth, c0 + int(rng.drawUniform(4.0, 60.0)));
        const int r1 = std::min(kHeight, r0 + int(rng.drawUniform(4.0, 60.0)));
        const double gray = rng.drawUniform(40.0, 180.0);
        for (int r = r0; r < r1; r++)
            std::fill(&px[size_t(r) * kWidth + c0], &px[size_t(r) * kWidth + c1], gray);
    }
    for (int k = 0; k < 800; k++) {
        const double bx = rng.drawUniform(0.0, kWidth), by = rng.drawUniform(0.0, kHeight);
        const double sigma = rng.drawUniform(1.5, 8.0), amp = rng.drawUniform(-50.0, 50.0);
        const int reach = int(4 * sigma) + 1;
        for (int r = std::max(0, int(by) - reach); r < std::min(kHeight, int(by) + reach); r++) {
            for (int c = std::max(0, int(bx) - reach); c < std::min(kWidth, int(bx) + reach); c++) {
                const double u = c - bx, v = r - by;
                px[size_t(r) * kWidth + c] +=
                    amp * std::exp(-(u * u + v * v) / (2 * sigma * sigma));
            }
        }
    }
    mrpt::img::CImage img(kWidth, kHeight, mrpt::img::CH_GRAY);
    for (int r = 0; r < kHeight; r++) {
        for (int c = 0; c < kWidth; c++) {
            img.ptrLine<uint8_t>(r)[c] =
                static_cast<uint8_t>(std::clamp(std::lround(px[size_t(r) * kWidth + c]), 0L, 255L));
        }
    }
    return img;
}

FastHessianDetector::TOptions options(int initial_step)
{
    FastHessianDetector::TOptions opts;
    opts.initial_step = initial_step;
    return opts;
}

// Integral image + fast-Hessian detection (default options; argument: initial step).
void BM_FastHessianDetect(benchmark::State& state)
{
    const auto img = scene();
    const FastHessianDetector detector(options(int(state.range(0))));
    size_t count = 0;
    for (auto _ : state) {
        const auto kps = detector.detect(IntegralImage(img));
        count = kps.size();
        benchmark::DoNotOptimize(kps.data());
    }
    state.counters["keypoints"] = double(count);
}
BENCHMARK(BM_FastHessianDetect)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// Integral image + detection + a U-SURF descriptor for every keypoint that fits in the image.
void BM_FastHessianDetectAndDescribe(benchmark::State& state)
{
    const auto img = scene();
    const FastHessianDetector detector(options(int(state.range(0))));
    size_t count = 0;
    for (auto _ : state) {
        const USurfDescriptor usurf(img);
        std::vector<USurfDescriptor::TDescriptor> descriptors;
        for (const auto& kp : detector.detect(usurf.integralImage())) {
            if (auto d = usurf.compute(kp.x, kp.y, kp.scale)) descriptors.push_back(*d);
        }
        count = descriptors.size();
        benchmark::DoNotOptimize(descriptors.data());
    }
    state.counters["descriptors"] = double(count);
}
BENCHMARK(BM_FastHessianDetectAndDescribe)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace
