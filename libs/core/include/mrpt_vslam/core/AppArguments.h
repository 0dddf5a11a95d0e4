#pragma once

#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/RunReport.h>

#include <cstdint>
#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** The command line shared by the driver apps (doc/app-conventions.md):
 *  `APP CONFIG.ini [RAWLOG] [--out DIR] [--seed N] [--threads N] [--set SECTION.KEY=VALUE]...
 *   [--ground-truth NAME] [--quiet] [--gui] [--help] [--version]`, and for the apps that take
 *  readings live (multirobot-vslam) `[--listen ENDPOINT]`.
 *
 *  Usage in main():
 *  1. `auto args = AppArguments::parse(argc, argv, "omni-fastslam", "FastSLAM 2.0 with ...");`
 *     inside `try { } catch (const UsageError& e) { print "APP: error: " + e.what(); return 2; }`;
 *  2. if `args.request != Request::Run`, print `args.message` on stdout and return 0;
 *  3. otherwise hand `args` to the app object.
 *  Parsing never prints and never exits.
 */
class AppArguments {
  public:
    enum class Request { Run, ShowHelp, ShowVersion };

    Request request = Request::Run;
    std::string message;  ///< help or version text when request != Run

    std::string appName;
    std::string configFile;                  ///< positional CONFIG (required)
    std::string rawlogFile;                  ///< positional RAWLOG; empty: config's `rawlog_file`
    std::string outDir;                      ///< `--out`, else defaultOutDir()
    uint32_t seed = 0;                       ///< `--seed`; 0: not given (see resolveSeed())
    unsigned threads = 0;                    ///< `--threads`; 0: every core
    std::vector<TConfigOverride> overrides;  ///< every `--set`, in order
    std::string groundTruth;                 ///< `--ground-truth`; empty: look beside the rawlog
    /// `--listen`: the ZeroMQ address the robots' readings arrive at, instead of a rawlog
    std::string listen;
    bool quiet = false;                    ///< `--quiet`: no progress line, no chatter
    bool gui = false;                      ///< `--gui`: live 3D view
    std::vector<std::string> commandLine;  ///< argv as given, for run.json

    /** Parses argv. Throws UsageError with a one-line reason ending in "(see APP --help)" for
     *  unknown options, a missing CONFIG, extra positionals, or a malformed `--seed`,
     *  `--threads` or `--set`, and for RAWLOG with `--listen`.
     *  \param live whether the app offers `--listen` */
    static AppArguments parse(int argc, const char* const* argv, const std::string& appName,
                              const std::string& description, bool live = false);

    /** `out/<appName>-<config file name without directory and extension>`. */
    static std::string defaultOutDir(const std::string& appName, const std::string& configFile);

    /** The seed to use: `--seed` if given (non-zero), else the config's `[section]
     *  random_seed` if non-zero, else 1. Throws UsageError naming the config unless that key
     *  (0 if absent) is an integer from 0 to 2³² − 1. */
    uint32_t resolveSeed(const CheckedConfigFile& cfg, const std::string& section) const;

    /** The rawlog to read: RAWLOG if given, else the config's `[section] rawlog_file`; with
     *  `--listen`, its address.
     *  Throws UsageError "CONFIG: no rawlog given (...)" when neither is there. */
    std::string resolveRawlog(const CheckedConfigFile& cfg, const std::string& section) const;

    /** Prefix `NAME` of the ground-truth files (doc/data-formats.md): groundTruthPrefixOf()
     *  `--ground-truth` if given, else of the rawlog's path. */
    std::string groundTruthPrefix(const std::string& rawlog) const;

    /** Records this run's inputs in its report: the command line, the configuration (file and
     *  effective text, `--set` included), the rawlog read, the seed and the threads used. */
    void describeInputs(RunReport& report, const std::string& effective_config,
                        const std::string& rawlog, uint32_t seed_used) const;
};

}  // namespace mrpt_vslam::core
