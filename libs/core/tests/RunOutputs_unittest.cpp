// The run folder's map and object files: written whole under their names, or not at all (no
// part-written PREFIX.tmp* file left when a file cannot be put in place).
#include <gtest/gtest.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt_vslam/core/RunOutputs.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {
std::vector<std::string> filesIn(const fs::path& dir)
{
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename());
    return names;
}
}  // namespace

TEST(RunOutputs, MapFilesAreWrittenWholeOrNotAtAll)
{
    const mrpt_vslam::test::ScratchFolder scratch("RunOutputs_unittest");
    mrpt::maps::CSimplePointsMap map;
    map.insertPoint(1, 2, 3);
    const fs::path ok = scratch.path() / "ok", blocked = scratch.path() / "blocked";
    fs::create_directories(ok);
    mrpt_vslam::core::saveFinalMap(map, ok.string());
    EXPECT_TRUE(fs::is_regular_file(ok / "map.txt"));
    EXPECT_TRUE(fs::is_regular_file(ok / "final_map.gz"));
    for (const auto& name : filesIn(ok)) EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;

    // a folder where map.txt goes: the rename fails, and no map.tmp* stays
    fs::create_directories(blocked / "map.txt");
    EXPECT_THROW(mrpt_vslam::core::saveFinalMap(map, blocked.string()), std::runtime_error);
    EXPECT_EQ(filesIn(blocked), std::vector<std::string>{"map.txt"});
    // the same for an object file
    fs::remove(blocked / "map.txt");
    fs::create_directories(blocked / "final_map.gz");
    EXPECT_THROW(mrpt_vslam::core::saveObjectGz(map, (blocked / "final_map.gz").string()),
                 std::runtime_error);
    EXPECT_EQ(filesIn(blocked), std::vector<std::string>{"final_map.gz"});
}
