// Runs the built vslam-sim binary like a user would and checks its files and its errors.
#include <gtest/gtest.h>
#include <mrpt_vslam/test/RawlogInfo.h>
#include <mrpt_vslam/test/RunCommand.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

using TRun = mrpt_vslam::test::TCommandResult;
using mrpt_vslam::test::processScratchFolder;

/// Runs a shell command, capturing stdout + stderr.
TRun runCommand(const std::string& command)
{
    return mrpt_vslam::test::runCommand(command, processScratchFolder() / "command.log");
}

TRun runSim(const std::string& args)
{
    return runCommand(std::string(MRPT_VSLAM_BIN_DIR "/vslam-sim ") + args);
}

/// Lines that are not `#` comments.
int dataLines(const fs::path& file)
{
    std::ifstream in(file);
    int n = 0;
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && line[0] != '#') n++;
    return n;
}

using mrpt_vslam::test::lineCount;
using mrpt_vslam::test::parseRawlogInfo;
using mrpt_vslam::test::TRawlogInfo;

/// Simulates 12 frames of the hall into a fresh directory once; returns the prefix.
std::string shortHall()
{
    static const std::string prefix = [] {
        const fs::path dir = processScratchFolder() / "short";
        fs::remove_all(dir);
        const TRun r =
            runSim("sports-hall --seed 4 --frames 12 --quiet --out " + (dir / "hall").string());
        EXPECT_EQ(r.exit_code, 0) << r.out;
        EXPECT_EQ(r.out, "");
        return (dir / "hall").string();
    }();
    return prefix;
}

/// Simulates 3 steps of the office with two robots into a fresh directory once; returns the
/// prefix.
std::string shortOffice()
{
    static const std::string prefix = [] {
        const fs::path dir = processScratchFolder() / "office";
        fs::remove_all(dir);
        const TRun r = runSim("office-team --robots 2 --seed 4 --frames 3 --quiet --out " +
                              (dir / "office").string());
        EXPECT_EQ(r.exit_code, 0) << r.out;
        EXPECT_EQ(r.out, "");
        return (dir / "office").string();
    }();
    return prefix;
}

}  // namespace

TEST(VslamSim, WritesTheDatasetFiles)
{
    const std::string prefix = shortHall();
    EXPECT_EQ(dataLines(prefix + ".groundtruth.tum"), 12);
    EXPECT_EQ(dataLines(prefix + ".odometry.tum"), 12);
    EXPECT_EQ(dataLines(prefix + ".landmarks.txt"), 14);
    EXPECT_GT(fs::file_size(prefix + ".rawlog"), 1000u);
    EXPECT_FALSE(fs::exists(prefix + ".rawlog.tmp"));
    int images = 0;
    for (const auto& e : fs::directory_iterator(prefix + "_Images"))
        images += e.path().extension() == ".png";
    EXPECT_EQ(images, 12);
}

TEST(VslamSim, StockRawlogEditReadsEveryFrame)
{
    if (!fs::exists("/usr/bin/rawlog-edit")) GTEST_SKIP() << "/usr/bin/rawlog-edit not installed";
    const std::string prefix = shortHall();
    const TRun r = runCommand("/usr/bin/rawlog-edit --info -i '" + prefix + ".rawlog'");
    EXPECT_EQ(r.exit_code, 0) << r.out;
    const TRawlogInfo info = parseRawlogInfo(r.out);
    EXPECT_EQ(info.fields.count("Overall number of objects")
                  ? info.fields.at("Overall number of objects")
                  : "",
              "24")
        << r.out;
    EXPECT_EQ(info.fields.count("Actions/SensoryFrame format")
                  ? info.fields.at("Actions/SensoryFrame format")
                  : "",
              "Yes")
        << r.out;
    const std::map<std::string, int> expected{
        {"GROUND_TRUTH", 12}, {"OMNICAM", 12}, {"OMNICAM_BEARINGS", 12}};
    EXPECT_EQ(info.sensor_counts, expected) << r.out;
    EXPECT_EQ(r.out.find("rror"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("xception"), std::string::npos) << r.out;
}

TEST(VslamSim, OfficeTeamWritesOneFileSetPerRobot)
{
    const std::string prefix = shortOffice();
    for (const std::string robot : {"R1", "R2"}) {
        EXPECT_EQ(dataLines(prefix + ".groundtruth_" + robot + ".tum"), 3) << robot;
        EXPECT_EQ(dataLines(prefix + ".odometry_" + robot + ".tum"), 3) << robot;
    }
    EXPECT_FALSE(fs::exists(prefix + ".groundtruth_R3.tum"));
    EXPECT_GT(dataLines(prefix + ".landmarks.txt"), 800);
    EXPECT_GT(fs::file_size(prefix + ".topview.png"), 1000u);
    EXPECT_FALSE(fs::exists(prefix + ".rawlog.tmp"));
    int images = 0;
    for (const auto& e : fs::directory_iterator(prefix + "_Images"))
        images += e.path().extension() == ".png";
    EXPECT_EQ(images, 3 * 2 * 2);  // steps × robots × (left, right)
    EXPECT_TRUE(fs::exists(prefix + "_Images/R2_STEREO_000002_R.png"));
}

TEST(VslamSim, StockRawlogEditReadsTheOfficeTeamRawlog)
{
    if (!fs::exists("/usr/bin/rawlog-edit")) GTEST_SKIP() << "/usr/bin/rawlog-edit not installed";
    const std::string prefix = shortOffice();
    const TRun r = runCommand("/usr/bin/rawlog-edit --info -i '" + prefix + ".rawlog'");
    EXPECT_EQ(r.exit_code, 0) << r.out;
    const TRawlogInfo info = parseRawlogInfo(r.out);
    EXPECT_EQ(info.fields.count("Overall number of objects")
                  ? info.fields.at("Overall number of objects")
                  : "",
              "18")
        << r.out;
    EXPECT_EQ(info.fields.count("Observations format") ? info.fields.at("Observations format") : "",
              "Yes")
        << r.out;
    const std::map<std::string, int> expected{{"R1_GROUND_TRUTH", 3}, {"R1_ODOM", 3},
                                              {"R1_STEREO", 3},       {"R2_GROUND_TRUTH", 3},
                                              {"R2_ODOM", 3},         {"R2_STEREO", 3}};
    EXPECT_EQ(info.sensor_counts, expected) << r.out;
    EXPECT_EQ(r.out.find("rror"), std::string::npos) << r.out;
}

TEST(VslamSim, OfficeTeamWithoutImagesAndWithThreeRobots)
{
    const fs::path dir = processScratchFolder() / "office3";
    fs::remove_all(dir);
    const TRun r =
        runSim("office-team --robots 3 --frames 4 --no-images --out " + (dir / "office").string());
    EXPECT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("4 frames, 3 robots"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("ground-truth corners"), std::string::npos) << r.out;
    EXPECT_EQ(dataLines(dir / "office.groundtruth_R3.tum"), 4);
    EXPECT_FALSE(fs::exists(dir / "office_Images"));
}

TEST(VslamSim, ProgressGoesToStderrUnlessQuiet)
{
    const TRun r = runSim("sports-hall --frames 3 --no-images --out " +
                          (processScratchFolder() / "progress" / "hall").string());
    EXPECT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("frame 3/3"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("3 frames"), std::string::npos) << r.out;
}

TEST(VslamSim, BadArgumentsFailWithOneLineErrorAndCode2)
{
    const std::string out = " --out " + (processScratchFolder() / "bad" / "x").string();
    for (const std::string& args :
         {std::string("gym") + out, std::string("sports-hall"), "sports-hall --frames 0" + out,
          "sports-hall --seed abc" + out, "sports-hall --set Lights.radiuss=0.3" + out,
          "sports-hall --set Lights.radius=-1" + out, "sports-hall --config /nonexistent.ini" + out,
          "sports-hall --bogus" + out, "sports-hall --set Lights=3" + out,
          "sports-hall --robots 2" + out, "office-team --robots 1" + out,
          "office-team --robots 4" + out, "office-team --robots 0" + out,
          "office-team --set World.texture_sed=3" + out,
          "office-team --set Trajectory_R2.waypoints=-1.75,0,-1.75,3" + out,
          "sports-hall --variant bogus" + out, "office-team --variant hard" + out}) {
        const TRun r = runSim(args);
        EXPECT_EQ(r.exit_code, 2) << args;  // usage error (doc/app-conventions.md)
        EXPECT_EQ(lineCount(r.out), 1) << args << "\n" << r.out;
        EXPECT_EQ(r.out.rfind("vslam-sim: error: ", 0), 0u) << args << "\n" << r.out;
    }
    EXPECT_FALSE(fs::exists(processScratchFolder() / "bad" / "x.rawlog"));
    EXPECT_FALSE(fs::exists(processScratchFolder() / "bad" / "x.rawlog.tmp"));
}

TEST(VslamSim, HardHallVariantReplacesItsKeysOnly)
{
    const fs::path dir = processScratchFolder() / "hard";
    fs::remove_all(dir);
    const TRun r = runSim(
        "sports-hall --variant hard --set Lights.height=4.5 --frames 3 "
        "--no-images --quiet --out " +
        (dir / "hall").string());
    ASSERT_EQ(r.exit_code, 0) << r.out;
    // the grid's 14 lights and the variant's two extra ones, at the --set height (--set last)
    std::ifstream in(dir / "hall.landmarks.txt");
    int n = 0;
    bool at_height = true;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream is(line);
        double id = 0, x = 0, y = 0, z = 0;
        is >> id >> x >> y >> z;
        at_height = at_height && z == 4.5;
        n++;
    }
    EXPECT_EQ(n, 16);
    EXPECT_TRUE(at_height);
    EXPECT_EQ(dataLines(dir / "hall.groundtruth.tum"), 3);
}

TEST(VslamSim, UnknownScenarioListsTheKnownOnes)
{
    const TRun r = runSim("gym --out " + (processScratchFolder() / "bad" / "y").string());
    EXPECT_NE(r.out.find("unknown scenario 'gym' (known: sports-hall, office-team, omni-views)"),
              std::string::npos)
        << r.out;
}

TEST(VslamSim, HelpExitsWithZero)
{
    const TRun r = runSim("--help");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_NE(r.out.find("--no-images"), std::string::npos) << r.out;
}
