// Bit-flipped and truncated variants of every shipped rawlog: reading them never crashes and
// never hangs; each ends cleanly or in one line naming the file.
#include <gtest/gtest.h>
#include <mrpt/maps/registerAllClasses.h>
#include <mrpt/vision/registerAllClasses.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/test/RunCommand.h>
#include <mrpt_vslam/test/RunFiles.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

namespace {
const std::string kData = std::string(MRPT_VSLAM_SOURCE_DIR) + "/datasets/";
const std::string kConfigs = std::string(MRPT_VSLAM_SOURCE_DIR) + "/share/mrpt-vslam/config/";

/// `flips` random bits of `bytes` (the first 20 bytes, the header, kept) inverted.
std::string flipped(std::string bytes, uint32_t seed, int flips)
{
    std::mt19937 rng(seed);
    std::uniform_int_distribution<size_t> at(20, bytes.size() - 9);
    std::uniform_int_distribution<int> bit(0, 7);
    for (int i = 0; i < flips; i++) bytes[at(rng)] ^= static_cast<char>(1 << bit(rng));
    return bytes;
}

void write(const std::string& file, const std::string& bytes)
{
    std::ofstream(file, std::ios::binary) << bytes;
}

struct TOutcome {
    int clean = 0, errors = 0, crashes = 0;
};

/// Reads `file` to the end; an error must be one line that names the file.
void readVariant(const std::string& file, TOutcome& outcome)
{
    try {
        mrpt_vslam::core::RawlogReader reader(file);
        for (mrpt_vslam::core::TRawlogEntry e; reader.next(e);) {
        }
        outcome.clean++;
    } catch (const std::runtime_error& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind(file + ": ", 0), 0u) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        (msg.find(" crashed (") != std::string::npos ? outcome.crashes : outcome.errors)++;
    }
}
}  // namespace

TEST(CorruptRawlog, VariantsOfEveryShippedRawlogEndCleanlyOrInOneLine)
{
    mrpt::maps::registerAllClasses_mrpt_maps();
    mrpt::vision::registerAllClasses_mrpt_vision();
    mrpt_vslam::test::ScratchFolder scratch("corrupt_rawlog_test");
    TOutcome all;
    for (const char* name : {"office-team/team2.rawlog", "office-team/team2-stereo-short.rawlog",
                             "sports-hall/hall.rawlog", "omni-views/rooms.rawlog",
                             "utias-mrclam/mrclam7-r123-0-300.rawlog"}) {
        const std::string original = mrpt_vslam::test::readBytes(kData + name);
        ASSERT_GT(original.size(), 100u) << name;
        TOutcome outcome;
        for (uint32_t seed = 1; seed <= 30; seed++) {
            const std::string file = scratch.file("flipped.rawlog");
            write(file, flipped(original, seed, 3));
            readVariant(file, outcome);
        }
        for (const double part : {0.1, 0.5, 0.9, 0.999}) {
            const std::string file = scratch.file("truncated.rawlog");
            write(file, original.substr(0, static_cast<size_t>(part * original.size())));
            TOutcome truncated;
            readVariant(file, truncated);
            EXPECT_EQ(truncated.clean, 0) << name << " cut at " << part;
            outcome.errors += truncated.errors;
            outcome.crashes += truncated.crashes;
        }
        std::cout << name << ": " << outcome.clean << " read to the end, " << outcome.errors
                  << " errors, " << outcome.crashes << " crashes of the deserialization caught\n";
        all.clean += outcome.clean;
        all.errors += outcome.errors;
        all.crashes += outcome.crashes;
    }
    // these variants include objects that crash MRPT's own deserialization when read in-process
    EXPECT_GE(all.crashes, 1);
}

// Rawlogs whose images are stored beside them (<NAME>_Images): a missing image file and one
// that is not an image end the run with one line naming the image, for each app that reads
// images (omni-fastslam in images mode, view-slam).
TEST(CorruptRawlog, MissingOrUnreadableExternalImagesGiveOneLine)
{
    namespace fs = std::filesystem;
    mrpt_vslam::test::ScratchFolder scratch("external_images_test");
    struct TCase {
        const char* app;
        const char* config;
        const char* dataset;  ///< under datasets/, without .rawlog
        const char* extra;
    };
    for (const TCase& c :
         {TCase{"omni-fastslam", "omni-fastslam/sports-hall.ini", "sports-hall/hall",
                " --set OmniFastSLAM.input=images"},
          TCase{"view-slam", "view-slam/omni-views.ini", "omni-views/rooms", ""}}) {
        const std::string name = fs::path(c.dataset).filename().string();
        const fs::path rawlog = scratch.path() / (name + ".rawlog");
        const fs::path images = scratch.path() / (name + "_Images");
        fs::copy_file(kData + c.dataset + ".rawlog", rawlog, fs::copy_options::overwrite_existing);
        for (const char* damage : {"missing", "garbage"}) {
            fs::remove_all(images);
            fs::copy(kData + c.dataset + "_Images", images);
            const fs::path victim = images / "OMNICAM_000003.png";
            ASSERT_TRUE(fs::exists(victim)) << victim;
            if (std::string(damage) == "missing")
                fs::remove(victim);
            else
                write(victim.string(), "not a PNG file");
            const auto r = mrpt_vslam::test::runCommand(
                std::string(MRPT_VSLAM_BIN_DIR "/") + c.app + " " + kConfigs + c.config + " " +
                    rawlog.string() + c.extra + " -q --out " + scratch.file("run"),
                scratch.path() / "command.log");
            EXPECT_NE(r.exit_code, 0) << c.app << ", " << damage << ": " << r.out;
            EXPECT_NE(r.out.find("OMNICAM_000003.png"), std::string::npos)
                << c.app << ", " << damage << ": " << r.out;
            EXPECT_LE(std::count(r.out.begin(), r.out.end(), '\n'), 1)
                << c.app << ", " << damage << ": " << r.out;
            EXPECT_FALSE(fs::exists(scratch.file("run/run.json")) &&
                         mrpt_vslam::test::readJson(scratch.file("run/run.json"))["completed"] ==
                             true)
                << c.app << ", " << damage;
        }
    }
}
