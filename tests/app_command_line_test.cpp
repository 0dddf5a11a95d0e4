// Every app's command line behaves alike (doc/app-conventions.md): --help and --version on
// stdout with exit 0, and a usage error as one line "APP: error: REASON (see APP --help)" with
// exit 2.
#include <gtest/gtest.h>
#include <mrpt_vslam/core/Version.h>
#include <mrpt_vslam/test/RunCommand.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <sstream>
#include <string>
#include <utility>

namespace {
const char* const kApps[] = {"omni-fastslam",   "multirobot-vslam", "view-slam",
                             "stereo-frontend", "vslam-sim",        "vslam-eval",
                             "vslam-plot",      "mrclam2rawlog",    "vslam-robot-node"};

mrpt_vslam::test::TCommandResult runApp(const std::string& app, const std::string& args)
{
    static const mrpt_vslam::test::ScratchFolder scratch("app_command_line_test");
    return mrpt_vslam::test::runCommand(std::string(MRPT_VSLAM_BIN_DIR) + "/" + app + " " + args,
                                        scratch.path() / (app + ".log"));
}
}  // namespace

TEST(AppCommandLine, AnUnknownOptionIsOneLineAndExitCodeTwo)
{
    for (const std::string app : kApps) {
        const auto r = runApp(app, "--bogus");
        EXPECT_EQ(r.exit_code, 2) << app;
        EXPECT_EQ(r.out, app + ": error: unknown option --bogus (see " + app + " --help)\n");
    }
}

TEST(AppCommandLine, VersionAndHelpGoToStdoutWithExitCodeZero)
{
    for (const std::string app : kApps) {
        const auto version = runApp(app, "--version 2>/dev/null");
        EXPECT_EQ(version.exit_code, 0) << app;
        EXPECT_EQ(version.out, app + " " + mrpt_vslam::core::projectVersion() + " (MRPT " +
                                   mrpt_vslam::core::mrptVersion() + ")\n");
        const auto help = runApp(app, "--help 2>/dev/null");
        EXPECT_EQ(help.exit_code, 0) << app;
        EXPECT_NE(help.out.find("--version"), std::string::npos) << app << "\n" << help.out;
    }
    // the SLAM apps' rawlog may be left out (the config's rawlog_file): the synopsis says so
    for (const std::string app : {"omni-fastslam", "multirobot-vslam", "view-slam"}) {
        const auto help = runApp(app, "--help 2>/dev/null");
        // TCLAP wraps the synopsis where the app's path puts the line's end
        std::string synopsis;
        std::istringstream words(help.out);
        for (std::string word; words >> word;) synopsis += word + " ";
        EXPECT_NE(synopsis.find("<CONFIG.ini> [<RAWLOG>]"), std::string::npos) << help.out;
    }
}

// A SLAM app given another one's config (its template, say) says whose it is, in one line.
TEST(AppCommandLine, ASlamAppNamesTheAppAnotherAppsConfigIsFor)
{
    const std::string configs = MRPT_VSLAM_SOURCE_DIR "/share/mrpt-vslam/config/";
    const std::pair<std::string, std::string> apps[] = {{"omni-fastslam", "OmniFastSLAM"},
                                                        {"multirobot-vslam", "MultiRobotVSLAM"},
                                                        {"view-slam", "ViewSLAM"}};
    const std::string templates[] = {"omni-fastslam/template.ini",
                                     "multirobot-vslam/range-bearing.ini",
                                     "view-slam/template.ini"};
    for (size_t i = 0; i < 3; i++)
        for (size_t j = 0; j < 3; j++) {
            if (i == j) continue;
            const auto& [app, section] = apps[i];
            const std::string config = configs + templates[j];
            const auto r = runApp(app, config + " none.rawlog");
            EXPECT_EQ(r.exit_code, 2) << app << " " << config;
            EXPECT_EQ(r.out, app + ": error: " + config + ": a config of " + apps[j].first + " ([" +
                                 apps[j].second + "]), not of " + app + " ([" + section + "])\n");
        }
}
