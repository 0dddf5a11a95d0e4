// One frame of the multi-robot stereo front-end (Gil et al. 2010): Harris corners, stereo
// correspondence, U-SURF descriptors, R_t and tracking against the previous frame; and the
// rectification of a pair whose calibration is not rectified.
#include <benchmark/benchmark.h>
#include <mrpt/img/CImage.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPose3DQuat.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/multirobot/StereoFrontEnd.h>
#include <mrpt_vslam/multirobot/StereoRectifier.h>

#include <algorithm>
#include <cstdint>
#include <vector>

using mrpt_vslam::multirobot::StereoFrontEnd;
using mrpt_vslam::multirobot::StereoRectifier;

namespace {

constexpr int kShift = 8;  ///< [px] image motion between the two frames

/** A cluttered wall: random rectangles of random gray levels on noise, 3 × 3 box-blurred. */
std::vector<uint8_t> texture(int width, int height)
{
    mrpt::random::CRandomGenerator rng(1);
    std::vector<uint8_t> raw(static_cast<size_t>(width * height));
    for (auto& v : raw) v = static_cast<uint8_t>(rng.drawUniform(100.0, 156.0));
    for (int k = 0; k < width * height / 120; k++) {
        const int c0 = int(rng.drawUniform(0.0, width)), r0 = int(rng.drawUniform(0.0, height));
        const int c1 = std::min(width, c0 + int(rng.drawUniform(3.0, 20.0)));
        const int r1 = std::min(height, r0 + int(rng.drawUniform(3.0, 20.0)));
        const auto gray = uint8_t(rng.drawUniform(0.0, 255.0));
        for (int r = r0; r < r1; r++) std::fill(&raw[r * width + c0], &raw[r * width + c1], gray);
    }
    std::vector<uint8_t> out(raw.size());
    for (int r = 1; r + 1 < height; r++)
        for (int c = 1; c + 1 < width; c++) {
            int s = 0;
            for (int dr = -1; dr <= 1; dr++)
                for (int dc = -1; dc <= 1; dc++) s += raw[(r + dr) * width + c + dc];
            out[r * width + c] = static_cast<uint8_t>(s / 9);
        }
    return out;
}

/** A fronto-parallel textured wall at 2 m seen by a stereo pair of `width` × 3/4 `width` px,
 *  f = 0.875·width px, B = 0.12 m. */
struct TWall {
    int width, height, disparity, tex_width;
    double f, baseline = 0.12;
    std::vector<uint8_t> tex;

    explicit TWall(int w)
        : width(w),
          height(w * 3 / 4),
          disparity(static_cast<int>(0.875 * w * 0.12 / 2.0)),
          tex_width(w + disparity + kShift),
          f(0.875 * w),
          tex(texture(tex_width, height))
    {
    }

    /// The pair whose left image shows texture columns x0 .. x0 + width − 1.
    mrpt::obs::CObservationStereoImages::Ptr frame(int x0) const
    {
        const auto window = [&](int first_col) {
            mrpt::img::CImage img(width, height, mrpt::img::CH_GRAY);
            for (int r = 0; r < height; r++)
                std::copy_n(&tex[r * tex_width + first_col], width, img.ptrLine<uint8_t>(r));
            return img;
        };
        auto obs = mrpt::obs::CObservationStereoImages::Create();
        obs->sensorLabel = "R1_STEREO";
        obs->imageLeft = window(x0);
        obs->imageRight = window(x0 + disparity);
        obs->hasImageRight = true;
        mrpt::img::TStereoCamera cam;
        cam.leftCamera.ncols = cam.rightCamera.ncols = width;
        cam.leftCamera.nrows = cam.rightCamera.nrows = height;
        cam.leftCamera.setIntrinsicParamsFromValues(f, f, (width - 1) / 2.0, (height - 1) / 2.0);
        cam.rightCamera = cam.leftCamera;
        cam.rightCameraPose = mrpt::math::TPose3DQuat(baseline, 0, 0, 1, 0, 0, 0);
        obs->setStereoCameraParams(cam);
        return obs;
    }
};

// One frame at the given size with the default [StereoFrontEnd] options; the two frames
// alternate so that every processed frame is tracked against the other.
void BM_StereoFrontEndFrame(benchmark::State& state)
{
    const TWall wall(static_cast<int>(state.range(0)));
    const auto a = wall.frame(0), b = wall.frame(kShift);
    StereoFrontEnd fe({});
    fe.process(*a);
    size_t frames = 0, points = 0, tracked = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(fe.process(frames % 2 == 0 ? *b : *a));
        frames++;
        points += fe.lastFrameStats().points;
        tracked += fe.lastFrameStats().tracked;
    }
    state.counters["corners"] = static_cast<double>(fe.lastFrameStats().corners);
    state.counters["points"] = static_cast<double>(points) / frames;
    state.counters["tracked"] = static_cast<double>(tracked) / frames;
}
BENCHMARK(BM_StereoFrontEndFrame)->Arg(320)->Arg(640)->Unit(benchmark::kMillisecond);

// The rectification of one pair of a head with lens distortion and its right camera turned by
// 1 deg (the maps made once, before the loop): what a frame of such a head costs on top.
void BM_StereoRectifierPair(benchmark::State& state)
{
    const TWall wall(static_cast<int>(state.range(0)));
    auto pair = wall.frame(0);
    auto cam = pair->getStereoCameraParams();
    cam.leftCamera.dist[0] = cam.rightCamera.dist[0] = -0.2;
    cam.rightCameraPose =
        mrpt::poses::CPose3DQuat(mrpt::poses::CPose3D(0.12, 0, 0, 0, 0.0175, 0)).asTPose();
    pair->setStereoCameraParams(cam);
    StereoRectifier rectifier;
    rectifier.rectify(*pair);
    for (auto _ : state) benchmark::DoNotOptimize(rectifier.rectify(*pair));
}
BENCHMARK(BM_StereoRectifierPair)->Arg(320)->Arg(640)->Unit(benchmark::kMillisecond);

}  // namespace
