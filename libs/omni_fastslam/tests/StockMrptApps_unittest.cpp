// MRPT reuse: stock MRPT apps with this library loaded as a plugin.
#include <gtest/gtest.h>
#include <mrpt/system/filesystem.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/RunOutputs.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <memory>

using namespace mrpt_vslam;

namespace {
/// Environment for a stock app: the sanitizer runtime first when this build uses one (stock apps
/// leak at exit, so leak checks are off there), then `preload`.
std::string stockAppEnv(const std::string& preload = {})
{
    const std::string runtime = SANITIZER_RUNTIME;
    const std::string libs = runtime.empty() ? preload : runtime + " " + preload;
    std::string env = libs.find_first_not_of(' ') == std::string::npos
                          ? std::string()
                          : "LD_PRELOAD=\"" + libs + "\" ";
    if (!runtime.empty()) env += "ASAN_OPTIONS=detect_leaks=0 ";
    return env;
}

/// Runs a shell command and returns what it printed (stdout and stderr).
std::string outputOf(const std::string& cmd)
{
    std::string out;
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((cmd + " 2>&1").c_str(), "r"), pclose);
    std::array<char, 512> buf{};
    while (pipe && fgets(buf.data(), buf.size(), pipe.get())) out += buf.data();
    return out;
}
}  // namespace

TEST(StockMrptApps, RawlogEditReadsTheMapOnlyWithThePlugin)
{
    if (!mrpt::system::fileExists("/usr/bin/rawlog-edit"))
        GTEST_SKIP() << "rawlog-edit not installed";
    const test::ScratchFolder scratch("StockRawlogEdit");
    omni_fastslam::CCeilingLightsMap map;
    map.addLandmark({1, 2, 6.5}, Eigen::Matrix3d::Identity() * 0.01);
    const auto file = scratch.file("final_map.gz");
    core::saveObjectGz(map, file);

    const auto without = outputOf(stockAppEnv() + "rawlog-edit --info -i " + file);
    EXPECT_NE(without.find("not registered"), std::string::npos) << without;
    const auto with =
        outputOf(stockAppEnv() + "rawlog-edit -p " + OMNI_FASTSLAM_PLUGIN + " --info -i " + file);
    EXPECT_EQ(with.find("not registered"), std::string::npos) << with;
    EXPECT_NE(with.find("Overall number of objects         : 1"), std::string::npos) << with;
}

// rbpf-slam, with the library preloaded, maps the sports-hall lights with CCeilingLightsMap (its
// frame starts at the origin).
TEST(StockMrptApps, RbpfSlamBuildsACeilingLightsMapWithThePluginPreloaded)
{
    if (!mrpt::system::fileExists("/usr/bin/rbpf-slam")) GTEST_SKIP() << "rbpf-slam not installed";
    const std::string src = MRPT_VSLAM_SOURCE_DIR;
    const test::ScratchFolder scratch("StockRbpfSlam");
    const std::string out = scratch.file("out");
    // rbpf-slam has no --set: a copy of the config names the output folder
    const std::string ini = out + ".ini";
    ASSERT_EQ(
        std::system(("sed 's#^logOutput_dir = .*#logOutput_dir = " + out + "#' " + src +
                     "/share/mrpt-vslam/config/omni-fastslam/rbpf-slam-sports-hall.ini > " + ini)
                        .c_str()),
        0);
    const std::string run = "cd " + src + "/datasets/sports-hall && " +
                            stockAppEnv(OMNI_FASTSLAM_PLUGIN) + "rbpf-slam " + ini +
                            " hall.rawlog > " + out + ".log 2>&1";
    ASSERT_EQ(std::system(run.c_str()), 0) << "see " << out << ".log";

    const auto map = core::LandmarkFile::load(
        out + "/finalMap_mrpt_vslam__omni_fastslam__CCeilingLightsMap_00.txt");
    // True lights in rbpf-slam's frame: the robot starts at the first ground-truth pose
    // (9, -3.25, 0) and rbpf-slam puts it at the origin.
    const auto gt = core::TumTrajectory::load(src + "/datasets/sports-hall/hall.groundtruth.tum");
    const auto& p0 = gt.poses.front();
    size_t near = 0;
    for (const auto& t :
         core::LandmarkFile::load(src + "/datasets/sports-hall/hall.landmarks.txt").landmarks) {
        const mrpt::math::TPoint3D in_start{t.position.x - p0.x, t.position.y - p0.y, t.position.z};
        for (const auto& e : map.landmarks)
            if ((e.position - in_start).norm() < 1.0) {
                near++;
                break;
            }
    }
    EXPECT_GE(map.size(), 10u);
    EXPECT_LE(map.size(), 18u);
    EXPECT_GE(near, 10u) << "lights within 1 m of a true light";
}
