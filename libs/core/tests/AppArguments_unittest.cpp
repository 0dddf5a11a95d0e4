#include <gtest/gtest.h>
#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/core/Version.h>

#include <string>
#include <vector>

using mrpt_vslam::core::AppArguments;
using mrpt_vslam::core::CheckedConfigFile;
using mrpt_vslam::core::UsageError;

namespace {

AppArguments parseArgs(std::vector<const char*> argv)
{
    return AppArguments::parse(static_cast<int>(argv.size()), argv.data(), "omni-fastslam",
                               "FastSLAM 2.0 with an omnidirectional camera.");
}

std::string usageErrorOf(std::vector<const char*> argv)
{
    try {
        parseArgs(std::move(argv));
    } catch (const UsageError& e) {
        return e.what();
    }
    return {};
}

}  // namespace

TEST(AppArguments, MinimalCommandLineGetsDefaults)
{
    const auto a = parseArgs({"omni-fastslam", "cfg/omni_sim.ini"});
    EXPECT_EQ(a.request, AppArguments::Request::Run);
    EXPECT_EQ(a.configFile, "cfg/omni_sim.ini");
    EXPECT_EQ(a.rawlogFile, "");
    EXPECT_EQ(a.outDir, "out/omni-fastslam-omni_sim");
    EXPECT_EQ(a.seed, 0u);
    EXPECT_EQ(a.threads, 0u);
    EXPECT_TRUE(a.overrides.empty());
    EXPECT_EQ(a.groundTruth, "");
    EXPECT_FALSE(a.quiet);
    EXPECT_FALSE(a.gui);
    EXPECT_EQ(a.commandLine, (std::vector<std::string>{"omni-fastslam", "cfg/omni_sim.ini"}));
}

TEST(AppArguments, AllOptionsAreParsed)
{
    const auto a =
        parseArgs({"omni-fastslam", "a.ini", "data/run.rawlog", "--out", "res/x", "--seed", "42",
                   "--threads", "3", "--set", "Filter.sampleSize=200", "--set",
                   "Map.opts.sigma=0.1", "--ground-truth", "gt.tum", "--quiet", "--gui"});
    EXPECT_EQ(a.configFile, "a.ini");
    EXPECT_EQ(a.rawlogFile, "data/run.rawlog");
    EXPECT_EQ(a.outDir, "res/x");
    EXPECT_EQ(a.seed, 42u);
    EXPECT_EQ(a.threads, 3u);
    ASSERT_EQ(a.overrides.size(), 2u);
    EXPECT_EQ(a.overrides[0].section, "Filter");
    EXPECT_EQ(a.overrides[0].key, "sampleSize");
    EXPECT_EQ(a.overrides[0].value, "200");
    EXPECT_EQ(a.overrides[1].section, "Map.opts");
    EXPECT_EQ(a.overrides[1].key, "sigma");
    EXPECT_EQ(a.groundTruth, "gt.tum");
    EXPECT_TRUE(a.quiet);
    EXPECT_TRUE(a.gui);
}

TEST(AppArguments, HelpIsReturnedNotPrinted)
{
    testing::internal::CaptureStdout();
    const auto a = parseArgs({"omni-fastslam", "--help"});
    EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
    EXPECT_EQ(a.request, AppArguments::Request::ShowHelp);
    EXPECT_NE(a.message.find("--ground-truth"), std::string::npos);
    EXPECT_NE(a.message.find("SECTION.KEY=VALUE"), std::string::npos);
    EXPECT_NE(a.message.find("omnidirectional camera"), std::string::npos);
}

TEST(AppArguments, VersionNamesProjectAndMrpt)
{
    const auto a = parseArgs({"omni-fastslam", "--version"});
    EXPECT_EQ(a.request, AppArguments::Request::ShowVersion);
    EXPECT_EQ(a.message, "omni-fastslam " + mrpt_vslam::core::projectVersion() + " (MRPT " +
                             mrpt_vslam::core::mrptVersion() + ")\n");
}

TEST(AppArguments, UsageErrorsAreOneLineAndPrintNothing)
{
    testing::internal::CaptureStderr();
    const std::string missing = usageErrorOf({"omni-fastslam"});
    const std::string unknown = usageErrorOf({"omni-fastslam", "a.ini", "--sed", "3"});
    const std::string extra = usageErrorOf({"omni-fastslam", "a.ini", "b.rawlog", "c"});
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    for (const auto& m : {missing, unknown, extra}) {
        EXPECT_EQ(m.find("omni-fastslam: "), std::string::npos) << m;  // the app prints its name
        EXPECT_NE(m.find("(see omni-fastslam --help)"), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
    EXPECT_NE(unknown.find("unknown option --sed"), std::string::npos) << unknown;
    EXPECT_NE(usageErrorOf({"omni-fastslam", "a.ini", "--qiet"}).find("unknown option --qiet"),
              std::string::npos);
}

TEST(AppArguments, MalformedSeedAndSetAreRejected)
{
    EXPECT_NE(usageErrorOf({"x", "a.ini", "--seed", "-3"}).find("--seed -3"), std::string::npos);
    EXPECT_NE(usageErrorOf({"x", "a.ini", "--seed", "1.5"}).find("--seed"), std::string::npos);
    EXPECT_NE(usageErrorOf({"x", "a.ini", "--seed", "4294967296"}).find("--seed"),
              std::string::npos);
    EXPECT_EQ(parseArgs({"x", "a.ini", "--seed", "4294967295"}).seed, 4294967295u);
    EXPECT_NE(usageErrorOf({"x", "a.ini", "--set", "noDot=1"}).find("--set noDot=1"),
              std::string::npos);
    EXPECT_NE(usageErrorOf({"x", "a.ini", "--set", "A.b"}).find("missing '='"), std::string::npos);
}

TEST(AppArguments, MalformedThreadCountsAreRejected)
{
    for (const char* bad : {"-1", "2.5", "x", "", "257", "99999"})
        EXPECT_NE(
            usageErrorOf({"x", "a.ini", "--threads", bad}).find(std::string("--threads ") + bad),
            std::string::npos)
            << bad;
    EXPECT_EQ(parseArgs({"x", "a.ini", "--threads", "256"}).threads, 256u);
    EXPECT_EQ(parseArgs({"x", "a.ini", "--threads", "0"}).threads, 0u);
}

TEST(AppArguments, SeedResolutionPrefersCommandLineThenConfigThenOne)
{
    // the seed `a` resolves with a config [App] of `line`
    const auto seedOf = [](const AppArguments& a, const std::string& line) {
        CheckedConfigFile cfg;
        cfg.loadText("[App]\n" + line + "\n", "a.ini");
        return a.resolveSeed(cfg, "App");
    };
    auto a = parseArgs({"x", "a.ini"});
    EXPECT_EQ(seedOf(a, ""), 1u);
    EXPECT_EQ(seedOf(a, "random_seed = 0"), 1u);
    EXPECT_EQ(seedOf(a, "random_seed = 7"), 7u);
    EXPECT_EQ(seedOf(a, "random_seed = 4294967295"), 4294967295u);
    a = parseArgs({"x", "a.ini", "--seed", "9"});
    EXPECT_EQ(seedOf(a, "random_seed = 7"), 9u);
    // a seed the config cannot hold is named, not wrapped, with --seed too
    for (const std::string bad : {"-3", "4294967296", "1.5", "abc"}) {
        try {
            seedOf(a, "random_seed = " + bad);
            ADD_FAILURE() << bad << ": no error";
        } catch (const UsageError& e) {
            const std::string named = "a.ini: [App] random_seed = " + bad + ": ";
            EXPECT_EQ(std::string(e.what()).substr(0, named.size()), named) << e.what();
        }
    }
}

TEST(AppArguments, DefaultOutDirUsesConfigStem)
{
    EXPECT_EQ(AppArguments::defaultOutDir("view-slam", "/data/configs/indoor.v2.ini"),
              "out/view-slam-indoor.v2");
    EXPECT_EQ(AppArguments::defaultOutDir("view-slam", "plain"), "out/view-slam-plain");
}

// The ground truth is looked for beside the rawlog, compressed or not, or where --ground-truth
// says, by the rawlog, the trajectory or the prefix (vslam-eval takes the same forms).
TEST(AppArguments, GroundTruthPrefixComesFromTheRawlogOrTheGivenName)
{
    const auto beside = parseArgs({"omni-fastslam", "c.ini"});
    for (const char* rawlog :
         {"data/hall.rawlog", "data/hall.rawlog.gz", "data/hall.RAWLOG", "data/hall"})
        EXPECT_EQ(beside.groundTruthPrefix(rawlog), "data/hall") << rawlog;
    EXPECT_EQ(beside.groundTruthPrefix("data/hall.log"), "data/hall.log");
    for (const char* given :
         {"gt/hall", "gt/hall.rawlog", "gt/hall.rawlog.gz", "gt/hall.groundtruth.tum"}) {
        const auto a = parseArgs({"omni-fastslam", "c.ini", "--ground-truth", given});
        EXPECT_EQ(a.groundTruthPrefix("data/hall.rawlog"), "gt/hall") << given;
    }
}

// --listen only where the app offers it (and its --help lists it), and not with a RAWLOG.
TEST(AppArguments, ListenIsForLiveAppsAndReplacesTheRawlog)
{
    const auto parseLive = [](std::vector<const char*> argv) {
        return AppArguments::parse(static_cast<int>(argv.size()), argv.data(), "multirobot-vslam",
                                   "Team SLAM.", true);
    };
    EXPECT_NE(usageErrorOf({"omni-fastslam", "a.ini", "--listen", "tcp://0.0.0.0:5555"})
                  .find("unknown option --listen"),
              std::string::npos);
    EXPECT_EQ(parseArgs({"omni-fastslam", "--help"}).message.find("--listen"), std::string::npos);
    EXPECT_NE(parseLive({"multirobot-vslam", "--help"}).message.find("--listen"),
              std::string::npos);
    const auto live = parseLive({"multirobot-vslam", "a.ini", "--listen", "tcp://0.0.0.0:5555"});
    EXPECT_EQ(live.listen, "tcp://0.0.0.0:5555");
    EXPECT_TRUE(live.rawlogFile.empty());
    try {
        parseLive({"multirobot-vslam", "a.ini", "b.rawlog", "--listen", "tcp://0.0.0.0:5555"});
        ADD_FAILURE() << "a RAWLOG with --listen was taken";
    } catch (const UsageError& e) {
        EXPECT_NE(std::string(e.what()).find("not both"), std::string::npos) << e.what();
    }
    EXPECT_THROW(parseLive({"multirobot-vslam", "a.ini", "--listen", ""}), UsageError);
}
