// The particle filters update their particles, and view-slam extracts its features, on several
// threads (--threads); the same seed must give the same run folder, byte for byte (timings
// aside), whatever the thread count.
#include <gtest/gtest.h>
#include <mrpt_vslam/test/RunCommand.h>
#include <mrpt_vslam/test/RunFiles.h>
#include <mrpt_vslam/test/SameRunFolders.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <string>
#include <vector>

using mrpt_vslam::test::readJson;

namespace {

const std::string kSource = MRPT_VSLAM_SOURCE_DIR;
const std::string kConfigs = kSource + "/share/mrpt-vslam/config/";

/** Runs `app args` with --threads 1 and 3 (more threads than this machine may have cores, so
 *  that the particles are split unevenly) and expects every file of the two run folders to be
 *  equal, but for run.json's timing and command line. */
void expectSameRunWithOneAndThreeThreads(const std::string& name, const std::string& app,
                                         const std::string& args)
{
    mrpt_vslam::test::ScratchFolder scratch("threads-" + name);
    std::vector<std::string> dirs;
    for (const int threads : {1, 3}) {
        dirs.push_back(scratch.file("run" + std::to_string(threads)));
        const auto r = mrpt_vslam::test::runCommand(
            std::string(MRPT_VSLAM_BIN_DIR "/") + app + " " + args + " -q --threads " +
                std::to_string(threads) + " --out " + dirs.back(),
            scratch.path() / "command.log");
        ASSERT_EQ(r.exit_code, 0) << r.out;
    }
    EXPECT_EQ(readJson(dirs[0] + "/run.json")["timing"]["threads"], 1);
    EXPECT_EQ(readJson(dirs[1] + "/run.json")["timing"]["threads"], 3);
    const size_t compared = mrpt_vslam::test::expectSameRunFolders(dirs[0], dirs[1]);
    EXPECT_GE(compared, 4u) << name;
}

}  // namespace

// FastSLAM 2.0 of omni-fastslam on the shipped hall (M = 10 of the shipped config, and 100).
TEST(ThreadCount, OmniFastSLAMGivesTheSameRun)
{
    const std::string hall = kSource + "/datasets/sports-hall/hall.rawlog";
    expectSameRunWithOneAndThreeThreads(
        "omni", "omni-fastslam", kConfigs + "omni-fastslam/sports-hall.ini " + hall + " --seed 2");
    expectSameRunWithOneAndThreeThreads("omni100", "omni-fastslam",
                                        kConfigs + "omni-fastslam/sports-hall.ini " + hall +
                                            " --seed 2 --set ParticleFilter.sampleSize=100");
}

// multirobot-vslam with both proposals on the short stereo sequence: the optimal proposal
// and the paper's (both hand out the ids of new landmarks after the parallel updates, then
// create them in parallel).
TEST(ThreadCount, MultiRobotVSLAMGivesTheSameRunWithBothProposals)
{
    const std::string data = kConfigs + "multirobot-vslam/office-team-2.ini " + kSource +
                             "/datasets/office-team/team2-stereo-short.rawlog --seed 4 --set "
                             "ParticleFilter.sampleSize=200";
    expectSameRunWithOneAndThreeThreads("optimal", "multirobot-vslam", data);
    expectSameRunWithOneAndThreeThreads(
        "standard", "multirobot-vslam",
        data + " --set ParticleFilter.PF_algorithm=pfStandardProposal");
}

// view-slam's feature extraction (response maps by rows, descriptors by batches of keypoints).
TEST(ThreadCount, ViewSLAMGivesTheSameRun)
{
    expectSameRunWithOneAndThreeThreads("view", "view-slam",
                                        kConfigs + "view-slam/omni-views.ini " + kSource +
                                            "/datasets/omni-views/rooms.rawlog --seed 2");
}
