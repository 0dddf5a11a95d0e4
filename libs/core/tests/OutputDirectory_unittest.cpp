#include <gtest/gtest.h>
#include <mrpt_vslam/core/OutputDirectory.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

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
