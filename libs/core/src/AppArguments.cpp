#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/system/filesystem.h>
#include <mrpt/system/string_utils.h>
#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/core/Version.h>

#include <limits>
#include <sstream>

namespace mrpt_vslam::core {
namespace {

/** Collects TCLAP's help text and errors instead of printing them. */
class CapturingOutput : public TCLAP::StdOutput {
public:
    explicit CapturingOutput(std::ostream& help_out) : TCLAP::StdOutput(help_out) {}

    void usage(TCLAP::CmdLineInterface& c) override
    {
        helpShown = true;
        TCLAP::StdOutput::usage(c);
    }
    void version(TCLAP::CmdLineInterface&) override { versionShown = true; }
    void failure(TCLAP::CmdLineInterface&, TCLAP::ArgException& e) override
    {
        error = e.argId().empty() || e.argId() == " " ? e.error() : e.error() + ": " + e.argId();
    }

    bool helpShown = false;
    bool versionShown = false;
    std::string error;
};

/** TCLAP takes any word it cannot match, even "--qiet", as a positional; catch those first. */
void rejectUnknownOptions(const std::vector<const char*>& args, TCLAP::CmdLine& cmd)
{
    for (size_t i = 1; i < args.size(); ++i) {
        const std::string word = args[i];
        if (word.size() < 2 || word[0] != '-') continue;
        if (word == "--") return;  // TCLAP: ignore the rest
        const TCLAP::Arg* known = nullptr;
        for (const TCLAP::Arg* arg : cmd.getArgList())
            if ((!arg->getFlag().empty() && word == "-" + arg->getFlag()) ||
                word == "--" + arg->getName())
                known = arg;
        if (known == nullptr) throw UsageError("unknown option " + word);
        if (known->isValueRequired()) ++i;
    }
}

uint32_t parseSeed(const std::string& text)
{
    const bool digits_only =
        !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
    if (digits_only && text.size() <= 10) {
        const unsigned long long v = std::stoull(text);
        if (v <= std::numeric_limits<uint32_t>::max()) return static_cast<uint32_t>(v);
    }
    throw UsageError("--seed " + text + ": expected an integer from 0 to 4294967295");
}

}  // namespace

AppArguments AppArguments::parse(int argc, const char* const* argv, const std::string& appName,
                                 const std::string& description)
{
    // TCLAP remembers in a process-wide flag that an optional positional was declared, and then
    // refuses the required CONFIG of any later parser; each parse starts afresh.
    TCLAP::OptionalUnlabeledTracker<>::alreadyOptional() = false;

    std::ostringstream help;
    CapturingOutput output(help);
    TCLAP::CmdLine cmd(description, ' ', projectVersion());
    // setOutput() does not free the default output object and the destructor then skips it.
    delete cmd.getOutput();
    cmd.setOutput(&output);

    TCLAP::UnlabeledValueArg<std::string> config("CONFIG", "Configuration file (.ini).", true, "",
                                                 "CONFIG.ini", cmd);
    TCLAP::UnlabeledValueArg<std::string> rawlog(
        "RAWLOG", "Dataset; if absent, the config's rawlog_file key.", false, "", "RAWLOG", cmd);
    TCLAP::ValueArg<std::string> out("", "out", "Output folder (default out/<app>-<config name>).",
                                     false, "", "DIR", cmd);
    TCLAP::ValueArg<std::string> seed(
        "", "seed", "Random seed; 0 (default) takes the config's random_seed, else 1.", false, "0",
        "N", cmd);
    TCLAP::MultiArg<std::string> set("", "set", "Overrides (or adds) a config key; repeatable.",
                                     false, "SECTION.KEY=VALUE", cmd);
    TCLAP::ValueArg<std::string> ground_truth(
        "", "ground-truth", "Ground truth NAME (default: found beside the rawlog).", false, "",
        "NAME", cmd);
    TCLAP::SwitchArg quiet("q", "quiet", "No progress line or log output.", cmd, false);
    TCLAP::SwitchArg gui("", "gui", "Live 3D view of the estimate while it runs.", cmd, false);

    AppArguments a;
    a.appName = appName;
    a.commandLine.assign(argv, argv + argc);
    const auto usage_error = [&](const std::string& why) {
        return UsageError(appName + ": " + why + " (see " + appName + " --help)");
    };

    std::vector<const char*> args(argv, argv + argc);
    try {
        rejectUnknownOptions(args, cmd);
    } catch (const UsageError& e) {
        throw usage_error(e.what());
    }
    const bool ok = cmd.parse(argc, args.data());
    if (!ok) {
        if (output.helpShown) {
            a.request = Request::ShowHelp;
            a.message = help.str();
        } else if (output.versionShown) {
            a.request = Request::ShowVersion;
            a.message = appName + " " + projectVersion() + " (MRPT " + mrptVersion() + ")\n";
        } else {
            throw usage_error(output.error);
        }
        return a;
    }
    try {
        a.configFile = config.getValue();
        a.rawlogFile = rawlog.getValue();
        a.outDir = out.isSet() ? out.getValue() : defaultOutDir(appName, a.configFile);
        a.seed = parseSeed(seed.getValue());
        for (const auto& s : set.getValue()) a.overrides.push_back(TConfigOverride::parse(s));
    } catch (const UsageError& e) {
        throw usage_error(e.what());
    }
    if (out.isSet() && a.outDir.empty()) throw usage_error("--out needs a folder name");
    a.groundTruth = ground_truth.getValue();
    a.quiet = quiet.getValue();
    a.gui = gui.getValue();
    return a;
}

std::string AppArguments::defaultOutDir(const std::string& appName, const std::string& configFile)
{
    return "out/" + appName + "-" +
           mrpt::system::extractFileName(configFile);  // name without directory and extension
}

uint32_t AppArguments::resolveSeed(uint32_t config_seed) const
{
    if (seed != 0) return seed;
    return config_seed != 0 ? config_seed : 1;
}

std::string AppArguments::resolveRawlog(const CheckedConfigFile& cfg,
                                        const std::string& section) const
{
    const std::string configured = cfg.read_string(section, "rawlog_file", "");  // always read
    const std::string file = rawlogFile.empty() ? configured : rawlogFile;
    if (file.empty())
        throw UsageError(cfg.name() + ": no rawlog given (argument RAWLOG or [" + section +
                         "] rawlog_file)");
    return file;
}

std::string AppArguments::groundTruthPrefix(const std::string& rawlog) const
{
    if (!groundTruth.empty()) return groundTruth;
    const std::string ext = ".rawlog";
    if (rawlog.size() > ext.size() &&
        mrpt::system::strCmpI(rawlog.substr(rawlog.size() - ext.size()), ext))
        return rawlog.substr(0, rawlog.size() - ext.size());
    return rawlog;
}

void AppArguments::describeInputs(RunReport& report, const std::string& effective_config,
                                  const std::string& rawlog, uint32_t seed_used) const
{
    report.setCommandLine(commandLine);
    report.setConfig(configFile, effective_config);
    report.setRawlog(rawlog);
    report.setSeed(seed_used);
}

}  // namespace mrpt_vslam::core
