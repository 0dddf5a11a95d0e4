// The particle filters update their particles, and view-slam extracts its features, on several
// threads (--threads); the same seed must give the same run folder, byte for byte (timings
// aside), whatever the thread count.
#include <gtest/gtest.h>
#include <mrpt_vslam/test/RunCommand.h>
#include <mrpt_vslam/test/RunFiles.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using mrpt_vslam::test::readBytes;
using mrpt_vslam::test::readJson;

namespace {

const std::string kSource = MRPT_VSLAM_SOURCE_DIR;
const std::string kConfigs = kSource + "/share/mrpt-vslam/config/";

/// The text without the last column of each line.
std::string withoutLastColumn(const std::string& text)
{
    std::istringstream in(text);
    std::string out;
    for (std::string line; std::getline(in, line);)
        out += line.substr(0, line.find_last_of(' ')) + "\n";
    return out;
}

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
    size_t compared = 0;
    for (const auto& entry : fs::directory_iterator(dirs[0])) {
        const std::string file = entry.path().filename().string();
        const std::string other = dirs[1] + "/" + file;
        ASSERT_TRUE(fs::exists(other)) << file;
        if (file == "run.json") {
            const auto a = readJson(entry.path().string()), b = readJson(other);
            EXPECT_EQ(a["timing"]["threads"], 1);
            EXPECT_EQ(b["timing"]["threads"], 3);
            EXPECT_EQ(a["counts"], b["counts"]);
            EXPECT_EQ(a["results"], b["results"]);
            continue;
        }
        // metrics.json names the files it scored: the first folder's name as the second's
        std::string first = readBytes(entry.path().string());
        for (size_t at = first.find(dirs[0]); at != std::string::npos;
             at = first.find(dirs[0], at + dirs[1].size()))
            first.replace(at, dirs[0].size(), dirs[1]);
        std::string second = readBytes(other);
        if (file == "steps.txt") {  // view-slam's last column: the step's time [ms]
            first = withoutLastColumn(first);
            second = withoutLastColumn(second);
        }
        EXPECT_EQ(first, second) << name << ": " << file;
        compared++;
    }
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
