#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/system/filesystem.h>
#include <mrpt/system/string_utils.h>
#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/EvalInputs.h>
#include <mrpt_vslam/core/ParallelFor.h>
#include <mrpt_vslam/core/TclapParse.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/core/Version.h>

#include <limits>
#include <optional>
#include <sstream>

namespace mrpt_vslam::core {
namespace {

constexpr unsigned long long kMaxThreads = 256;

/// `text` as a whole decimal number from 0 to `max` (digits only), or nullopt.
std::optional<unsigned long long> parseDecimal(const std::string& text, unsigned long long max)
{
    // at most 19 digits: no overflow of unsigned long long
    if (text.empty() || text.size() > 19 ||
        text.find_first_not_of("0123456789") != std::string::npos)
        return std::nullopt;
    const unsigned long long v = std::stoull(text);
    return v <= max ? std::optional(v) : std::nullopt;
}

uint32_t parseSeed(const std::string& text)
{
    if (const auto v = parseDecimal(text, std::numeric_limits<uint32_t>::max()))
        return static_cast<uint32_t>(*v);
    throw UsageError("--seed " + text + ": expected an integer from 0 to 4294967295");
}

unsigned parseThreads(const std::string& text)
{
    if (const auto v = parseDecimal(text, kMaxThreads)) return static_cast<unsigned>(*v);
    throw UsageError("--threads " + text + ": expected an integer from 0 (every core) to " +
                     std::to_string(kMaxThreads));
}

/// A positional argument that may be left out, shown as [<NAME>] in the synopsis, where TCLAP
/// shows <NAME> as for a required one.
class OptionalPositional : public TCLAP::UnlabeledValueArg<std::string> {
  public:
    using TCLAP::UnlabeledValueArg<std::string>::UnlabeledValueArg;
    std::string shortID(const std::string& value) const override
    {
        return "[" + TCLAP::UnlabeledValueArg<std::string>::shortID(value) + "]";
    }
};

}  // namespace

AppArguments AppArguments::parse(int argc, const char* const* argv, const std::string& appName,
                                 const std::string& description, bool live)
{
    // TCLAP remembers in a process-wide flag that an optional positional was declared, and then
    // refuses the required CONFIG of any later parser; each parse starts afresh.
    TCLAP::OptionalUnlabeledTracker<>::alreadyOptional() = false;

    TCLAP::CmdLine cmd(description, ' ', projectVersion());

    TCLAP::UnlabeledValueArg<std::string> config("CONFIG", "Configuration file (.ini).", true, "",
                                                 "CONFIG.ini", cmd);
    OptionalPositional rawlog("RAWLOG", "Dataset; if absent, the config's rawlog_file key.", false,
                              "", "RAWLOG", cmd);
    TCLAP::ValueArg<std::string> out("", "out", "Output folder (default out/<app>-<config name>).",
                                     false, "", "DIR", cmd);
    TCLAP::ValueArg<std::string> seed(
        "", "seed", "Random seed; 0 (default) takes the config's random_seed, else 1.", false, "0",
        "N", cmd);
    TCLAP::ValueArg<std::string> threads(
        "", "threads",
        "Threads for the filter's updates; 0 (default): every core. The results do not depend "
        "on it.",
        false, "0", "N", cmd);
    TCLAP::MultiArg<std::string> set("", "set", "Overrides (or adds) a config key; repeatable.",
                                     false, "SECTION.KEY=VALUE", cmd);
    TCLAP::ValueArg<std::string> ground_truth(
        "", "ground-truth",
        "Ground truth NAME, NAME.rawlog or NAME.groundtruth.tum (default: found beside "
        "the rawlog).",
        false, "", "NAME", cmd);
    // declared only where the app offers it, so that --help lists it only there
    std::optional<TCLAP::ValueArg<std::string>> listen;
    if (live)
        listen.emplace("", "listen",
                       "Runs the filter live on the readings that robot nodes (vslam-robot-node) "
                       "stream to this ZeroMQ address, e.g. tcp://*:5555, instead of a rawlog "
                       "(doc/team-online.md).",
                       false, "", "ENDPOINT", cmd);
    TCLAP::SwitchArg quiet(
        "q", "quiet", "No progress line or log output (errors and warnings still go to stderr).",
        cmd, false);
    TCLAP::SwitchArg gui("", "gui",
                         "Live 3D view of the estimate while it runs; at the end the window stays "
                         "open until closed (unless --quiet).",
                         cmd, false);

    AppArguments a;
    a.appName = appName;
    a.commandLine.assign(argv, argv + argc);
    const auto usage_error = [&](const std::string& why) {
        return UsageError(why + " (see " + appName + " --help)");
    };

    const TclapOutcome outcome = parseTclap(cmd, argc, argv, appName, a.message);
    if (outcome == TclapOutcome::ShowHelp) {
        a.request = Request::ShowHelp;
        return a;
    }
    if (outcome == TclapOutcome::ShowVersion) {
        a.request = Request::ShowVersion;
        return a;
    }
    try {
        a.configFile = config.getValue();
        a.rawlogFile = rawlog.getValue();
        a.outDir = out.isSet() ? out.getValue() : defaultOutDir(appName, a.configFile);
        a.seed = parseSeed(seed.getValue());
        a.threads = parseThreads(threads.getValue());
        for (const auto& s : set.getValue()) a.overrides.push_back(TConfigOverride::parse(s));
    } catch (const UsageError& e) {
        throw usage_error(e.what());
    }
    if (out.isSet() && a.outDir.empty()) throw usage_error("--out needs a folder name");
    a.groundTruth = ground_truth.getValue();
    if (listen) a.listen = listen->getValue();
    if (listen && listen->isSet() && a.listen.empty())
        throw usage_error("--listen needs an address such as tcp://*:5555");
    if (!a.listen.empty() && !a.rawlogFile.empty())
        throw usage_error("give a RAWLOG or --listen, not both");
    a.quiet = quiet.getValue();
    a.gui = gui.getValue();
    return a;
}

std::string AppArguments::defaultOutDir(const std::string& appName, const std::string& configFile)
{
    return "out/" + appName + "-" +
           mrpt::system::extractFileName(configFile);  // name without directory and extension
}

uint32_t AppArguments::resolveSeed(const CheckedConfigFile& cfg, const std::string& section) const
{
    const std::string text = mrpt::system::trim(cfg.read_string(section, "random_seed", "0"));
    const auto configured = parseDecimal(text, std::numeric_limits<uint32_t>::max());
    if (!configured)  // read always, so that a wrong value is named with --seed too
        throw UsageError(cfg.name() + ": [" + section + "] random_seed = " + text +
                         ": expected an integer from 0 to 4294967295");
    if (seed != 0) return seed;
    return *configured != 0 ? static_cast<uint32_t>(*configured) : 1;
}

std::string AppArguments::resolveRawlog(const CheckedConfigFile& cfg,
                                        const std::string& section) const
{
    const std::string configured = cfg.read_string(section, "rawlog_file", "");  // always read
    if (!listen.empty()) return listen;
    const std::string file = rawlogFile.empty() ? configured : rawlogFile;
    if (file.empty())
        throw UsageError(cfg.name() + ": no rawlog given (argument RAWLOG or [" + section +
                         "] rawlog_file)");
    return file;
}

std::string AppArguments::groundTruthPrefix(const std::string& rawlog) const
{
    return groundTruthPrefixOf(groundTruth.empty() ? rawlog : groundTruth);
}

void AppArguments::describeInputs(RunReport& report, const std::string& effective_config,
                                  const std::string& rawlog, uint32_t seed_used) const
{
    report.setCommandLine(commandLine);
    report.setConfig(configFile, effective_config);
    report.setRawlog(rawlog);
    report.setSeed(seed_used);
    report.setThreads(resolveThreadCount(threads));
}

}  // namespace mrpt_vslam::core
