// Every run writes options.ini: each key the app read, with the value it used (the
// configuration's or the app's default). Given back as the configuration, with the same seed,
// it must give the same run, byte for byte (timings aside): the record of a run's options is
// whole. On the shipped configurations and the templates of the three apps.
#include <gtest/gtest.h>
#include <mrpt_vslam/test/RunCommand.h>
#include <mrpt_vslam/test/RunFiles.h>
#include <mrpt_vslam/test/SameRunFolders.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <string>

namespace {

const std::string kSource = MRPT_VSLAM_SOURCE_DIR;
const std::string kConfigs = kSource + "/share/mrpt-vslam/config/";

/** Runs `app config rawlog extra`, then `app <its options.ini> rawlog` with the same seed, and
 *  expects the same run folder (but for the configuration files themselves). \return the first
 *  run's options.ini */
std::string expectSameRunFromItsOptions(const std::string& name, const std::string& app,
                                        const std::string& config, const std::string& rawlog,
                                        const std::string& extra = "")
{
    mrpt_vslam::test::ScratchFolder scratch("options-" + name);
    const std::string first = scratch.file("from-config"), second = scratch.file("from-options");
    const auto run = [&](const std::string& args) {
        return mrpt_vslam::test::runCommand(
            std::string(MRPT_VSLAM_BIN_DIR "/") + app + " " + args + " --seed 3 -q",
            scratch.path() / "command.log");
    };
    auto r = run(config + " " + rawlog + " --out " + first + extra);
    EXPECT_EQ(r.exit_code, 0) << r.out;
    if (r.exit_code != 0) return "";
    const std::string options = mrpt_vslam::test::readBytes(first + "/options.ini");
    EXPECT_NE(options.find("# not set: the program's defaults"), std::string::npos) << name;
    r = run(first + "/options.ini " + rawlog + " --out " + second);
    EXPECT_EQ(r.exit_code, 0) << r.out;
    if (r.exit_code != 0) return options;
    // the second run set every key: its options.ini has the same values, none at a default
    EXPECT_EQ(mrpt_vslam::test::readBytes(second + "/options.ini")
                  .find("# not set: the program's defaults"),
              std::string::npos)
        << name;
    const size_t compared =
        mrpt_vslam::test::expectSameRunFolders(first, second, {"config.ini", "options.ini"});
    EXPECT_GE(compared, 4u) << name;
    return options;
}

}  // namespace

TEST(OptionsInUse, OmniFastSLAMRunsTheSameFromThem)
{
    const std::string hall = kSource + "/datasets/sports-hall/hall.rawlog";
    expectSameRunFromItsOptions("omni", "omni-fastslam", kConfigs + "omni-fastslam/sports-hall.ini",
                                hall);
    const std::string options = expectSameRunFromItsOptions(
        "omni-template", "omni-fastslam", kConfigs + "omni-fastslam/template.ini", hall);
    // the template sets only the number of particles: the keys MRPT requires besides take the
    // recommended values
    const size_t section = options.find("[ParticleFilter]");
    const size_t defaults = options.find("# not set", section);
    const size_t next = options.find("\n[", section);
    for (const std::string key :
         {"PF_algorithm = pfOptimalProposal", "resamplingMethod = prSystematic", "BETA = 0.5",
          "adaptiveSampleSize = false"}) {
        const size_t at = options.find("\n" + key + "\n", section);
        EXPECT_TRUE(at != std::string::npos && at > defaults && at < next) << key << "\n"
                                                                           << options;
    }
}

// The stereo front-end's options too, and the smoothing's (mrclam.ini) on the MRCLAM cut.
TEST(OptionsInUse, MultiRobotVSLAMRunsTheSameFromThem)
{
    expectSameRunFromItsOptions("stereo", "multirobot-vslam",
                                kConfigs + "multirobot-vslam/office-team-2.ini",
                                kSource + "/datasets/office-team/team2-stereo-short.rawlog",
                                " --set ParticleFilter.sampleSize=200");
    expectSameRunFromItsOptions(
        "mrclam", "multirobot-vslam", kConfigs + "multirobot-vslam/mrclam.ini",
        kSource + "/datasets/utias-mrclam/mrclam7-r123-0-300.rawlog",
        " --set ParticleFilter.sampleSize=200 --set MultiRobotVSLAM.filter_runs=1");
}

TEST(OptionsInUse, ViewSLAMRunsTheSameFromThem)
{
    const std::string rooms = kSource + "/datasets/omni-views/rooms.rawlog";
    expectSameRunFromItsOptions("views", "view-slam", kConfigs + "view-slam/omni-views.ini", rooms);
    expectSameRunFromItsOptions("views-template", "view-slam", kConfigs + "view-slam/template.ini",
                                rooms);
}
