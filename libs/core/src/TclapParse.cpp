#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt_vslam/core/TclapParse.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/core/Version.h>

#include <sstream>
#include <vector>

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

}  // namespace

TclapOutcome parseTclap(TCLAP::CmdLine& cmd, int argc, const char* const* argv,
                        const std::string& app_name, std::string& message)
{
    const auto usage_error = [&](const std::string& why) {
        return UsageError(why + " (see " + app_name + " --help)");
    };
    std::ostringstream help_text;
    CapturingOutput output(help_text);
    // setOutput() does not free the default output object and the destructor then skips it.
    delete cmd.getOutput();
    cmd.setOutput(&output);

    std::vector<const char*> args(argv, argv + argc);
    try {
        rejectUnknownOptions(args, cmd);
    } catch (const UsageError& e) {
        throw usage_error(e.what());
    }
    if (cmd.parse(argc, args.data())) return TclapOutcome::Parsed;
    if (output.helpShown) {
        message = help_text.str();
        return TclapOutcome::ShowHelp;
    }
    if (output.versionShown) {
        message = versionLine(app_name);
        return TclapOutcome::ShowVersion;
    }
    throw usage_error(output.error);
}

}  // namespace mrpt_vslam::core
