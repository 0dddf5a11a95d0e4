#include <benchmark/benchmark.h>
#include <mrpt/img/CImage.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/USurfDescriptor.h>

#include <algorithm>
#include <cstdint>
#include <vector>

using mrpt_vslam::core::USurfDescriptor;

namespace {

constexpr int kWidth = 640, kHeight = 480, kKeypoints = 500;

/// Deterministic 640 × 480 texture of random overlapping rectangles.
mrpt::img::CImage texture()
{
    mrpt::random::CRandomGenerator rng(1);
    mrpt::img::CImage img(kWidth, kHeight, mrpt::img::CH_GRAY);
    for (int r = 0; r < kHeight; r++) std::fill_n(img.ptrLine<uint8_t>(r), kWidth, uint8_t(128));
    for (int k = 0; k < kWidth * kHeight / 150; k++) {
        const int c0 = int(rng.drawUniform(0.0, kWidth)), r0 = int(rng.drawUniform(0.0, kHeight));
        const int c1 = std::min(kWidth, c0 + int(rng.drawUniform(2.0, 30.0)));
        const int r1 = std::min(kHeight, r0 + int(rng.drawUniform(2.0, 30.0)));
        const auto gray = uint8_t(rng.drawUniform(0.0, 255.0));
        for (int r = r0; r < r1; r++)
            std::fill(img.ptrLine<uint8_t>(r) + c0, img.ptrLine<uint8_t>(r) + c1, gray);
    }
    return img;
}

struct TKeypoint {
    double x, y, scale;
};

/// 500 keypoints with scales in [1.2, 3.2] px, all far enough from the border.
std::vector<TKeypoint> keypoints()
{
    mrpt::random::CRandomGenerator rng(2);
    std::vector<TKeypoint> kps;
    for (int k = 0; k < kKeypoints; k++) {
        const double s = rng.drawUniform(1.2, 3.2), margin = 10.5 * s;
        kps.push_back({rng.drawUniform(margin, kWidth - 1 - margin),
                       rng.drawUniform(margin, kHeight - 1 - margin), s});
    }
    return kps;
}

void BM_USurfIntegralImage(benchmark::State& state)
{
    const auto img = texture();
    for (auto _ : state) benchmark::DoNotOptimize(USurfDescriptor(img));
}
BENCHMARK(BM_USurfIntegralImage)->Unit(benchmark::kMicrosecond);

// 500 descriptors on one 640 × 480 image (integral image built once, outside the loop).
void BM_USurfDescribe500(benchmark::State& state)
{
    const USurfDescriptor usurf(texture());
    const auto kps = keypoints();
    for (auto _ : state) {
        for (const auto& kp : kps) benchmark::DoNotOptimize(usurf.compute(kp.x, kp.y, kp.scale));
    }
    state.SetItemsProcessed(state.iterations() * kKeypoints);
}
BENCHMARK(BM_USurfDescribe500)->Unit(benchmark::kMicrosecond);

// Brute-force ratio-test matching of 500 descriptors against 500.
void BM_USurfMatch500x500(benchmark::State& state)
{
    const USurfDescriptor usurf(texture());
    std::vector<USurfDescriptor::TDescriptor> descriptors;
    for (const auto& kp : keypoints()) {
        if (auto d = usurf.compute(kp.x, kp.y, kp.scale)) descriptors.push_back(*d);
    }
    for (auto _ : state) {
        for (const auto& d : descriptors) {
            benchmark::DoNotOptimize(USurfDescriptor::bestMatch(d, descriptors, 0.8));
        }
    }
    state.SetItemsProcessed(state.iterations() * int64_t(descriptors.size()));
}
BENCHMARK(BM_USurfMatch500x500)->Unit(benchmark::kMillisecond);

}  // namespace
