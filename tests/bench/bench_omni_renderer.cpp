// One 640×480 omnidirectional image of the omni-views world (vslam-sim, Valiente et al. 2015):
// a ray per pixel through the unified sphere model, nearest face, bilinear texture sample,
// pixel noise.
#include <benchmark/benchmark.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt_vslam/sim/OmniViewsScenario.h>

namespace {

void BM_OmniRenderFrame(benchmark::State& state)
{
    mrpt_vslam::sim::OmniViewsScenario s;
    s.loadConfig(mrpt::config::CConfigFile(MRPT_VSLAM_SOURCE_DIR
                                           "/share/mrpt-vslam/config/vslam-sim/omni-views.ini"));
    const auto model = s.world.build(s.textures);
    const auto path = s.trajectory.generate(s.trajectory.frames);
    size_t k = 0;
    for (auto _ : state) {
        const mrpt::poses::CPose3D camera =
            mrpt::poses::CPose3D(mrpt::poses::CPose2D(path[k])) + s.camera_on_robot;
        benchmark::DoNotOptimize(s.renderer.renderView(model.scene, camera));
        k = (k + 37) % path.size();
    }
}

}  // namespace

BENCHMARK(BM_OmniRenderFrame)->Unit(benchmark::kMillisecond);
