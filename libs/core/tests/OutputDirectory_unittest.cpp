#include <gtest/gtest.h>
#include <mrpt_vslam/core/OutputDirectory.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using mrpt_vslam::core::OutputDirectory;

namespace {
fs::path scratch()
{
    const fs::path p =
        fs::path(::testing::TempDir()) / ("OutputDirectory_unittest_" + std::to_string(::getpid()));
    fs::remove_all(p);
    return p;
}
}  // namespace

TEST(OutputDirectory, CreatesNestedFolders)
{
    const fs::path root = scratch();
    const std::string dir = (root / "a" / "b" / "run1").string();
    const OutputDirectory out(dir);
    EXPECT_TRUE(fs::is_directory(dir));
    EXPECT_EQ(out.path(), dir);
    EXPECT_EQ(out.file("run.json"), dir + "/run.json");
    const OutputDirectory again(dir);  // an existing folder is fine
    EXPECT_EQ(again.path(), dir);
    fs::remove_all(root);
}

TEST(OutputDirectory, FailsClearlyWhenAFileIsInTheWay)
{
    const fs::path root = scratch();
    fs::create_directories(root);
    const std::string blocker = (root / "file").string();
    std::ofstream(blocker) << "x";
    for (const std::string& dir : {blocker, blocker + "/sub"}) {
        try {
            OutputDirectory out(dir);
            ADD_FAILURE() << "no exception for " << dir;
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()).rfind(dir + ": cannot create output folder: ", 0), 0u)
                << e.what();
        }
    }
    EXPECT_THROW(OutputDirectory(""), std::runtime_error);
    fs::remove_all(root);
}

TEST(OutputDirectory, RunFilesAreTheNamesTheAppsWrite)
{
    for (const char* name : {"run.json",
                             "metrics.json",
                             "config.ini",
                             "options.ini",
                             "final.3Dscene",
                             "final_map.gz",
                             "steps.txt",
                             "observations.txt",
                             "paths.png",
                             "errors.png",
                             "landmark_errors.png",
                             "estimated_path.tum",
                             "estimated_path_R1.tum",
                             "odometry_path_R12.tum",
                             "filter_path.tum",
                             "filter_path_R2.tum",
                             "map.txt",
                             "map_descriptors.txt",
                             "map_views.txt",
                             "particle_map.txt",
                             "particle_map_descriptors.txt",
                             "filter_map.txt"})
        EXPECT_TRUE(OutputDirectory::isRunFile(name)) << name;
    for (const char* name :
         {"hall.rawlog", "hall.groundtruth.tum", "hall.landmarks.txt", "notes.txt", "mapping.txt",
          "map.tum", "estimated_path", "estimated_path_.tum", "estimated_paths.tum",
          "estimated_path.txt", "map_.txt", "run.json.tmp", "final.3Dscene.tmp", "my_config.ini",
          "paths.png.bak", "my_map.txt", ""})
        EXPECT_FALSE(OutputDirectory::isRunFile(name)) << name;
}

TEST(OutputDirectory, RemovesAnEarlierRunAndNothingElse)
{
    const fs::path root = scratch();
    const OutputDirectory out(root.string());
    const std::vector<std::string> run = {"run.json", "estimated_path_R2.tum", "map.txt",
                                          "final.3Dscene", "filter_path.tum"};
    const std::vector<std::string> others = {"hall.rawlog", "notes.txt", "map.txt.tmp"};
    for (const auto& name : run) std::ofstream(out.file(name)) << "x";
    for (const auto& name : others) std::ofstream(out.file(name)) << "x";
    fs::create_directories(out.file("paths.png"));  // a folder of that name stays
    EXPECT_EQ(out.removeEarlierRun(), run.size());
    for (const auto& name : run) EXPECT_FALSE(fs::exists(out.file(name))) << name;
    for (const auto& name : others) EXPECT_TRUE(fs::exists(out.file(name))) << name;
    EXPECT_TRUE(fs::is_directory(out.file("paths.png")));
    EXPECT_EQ(out.removeEarlierRun(), 0u);
    fs::remove_all(root);
}

TEST(OutputDirectory, TellsAnInputThatTheRunWouldWriteOver)
{
    const fs::path root = scratch();
    const OutputDirectory out((root / "run").string());
    EXPECT_TRUE(out.holdsRunFile(out.file("config.ini")));
    EXPECT_TRUE(out.holdsRunFile((root / "run" / ".." / "run" / "map.txt").string()));
    EXPECT_FALSE(out.holdsRunFile(out.file("my.ini")));
    EXPECT_FALSE(out.holdsRunFile((root / "config.ini").string()));
    EXPECT_FALSE(out.holdsRunFile("tcp://*:5555"));
    fs::remove_all(root);
}
