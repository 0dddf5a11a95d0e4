#include "SimCommandLine.h"

#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/ScenarioFactory.h>

namespace {

/// Keeps TCLAP's usage text for --help but turns parse failures into one exception line.
class OneLineErrorOutput : public TCLAP::StdOutput {
  public:
    void failure(TCLAP::CmdLineInterface&, TCLAP::ArgException& e) override
    {
        error = e.argId().empty() || e.argId() == " " ? e.error() : e.argId() + ": " + e.error();
        // TCLAP's "Argument: (--x)" identifiers read better without the prefix.
        const std::string prefix = "Argument: ";
        if (error.rfind(prefix, 0) == 0) error = error.substr(prefix.size());
    }
    std::string error;
};

std::string scenarioList()
{
    std::string list;
    for (const std::string& n : mrpt_vslam::sim::knownScenarios())
        list += (list.empty() ? "" : ", ") + n;
    return list;
}

}  // namespace

std::optional<TSimCommandLine> parseSimCommandLine(int argc, char** argv)
{
    TCLAP::CmdLine cmd("vslam-sim: writes a simulated dataset (rawlog, images, ground truth)", ' ',
                       "0.1");
    OneLineErrorOutput output;
    // setOutput() does not free the default output CmdLine allocated; free it here.
    delete cmd.getOutput();
    cmd.setOutput(&output);
    TCLAP::UnlabeledValueArg<std::string> scenario("scenario", "Scenario: " + scenarioList(), true,
                                                   "", "SCENARIO", cmd);
    TCLAP::ValueArg<std::string> out("o", "out", "Output prefix DIR/NAME (writes NAME.rawlog, ...)",
                                     true, "", "DIR/NAME", cmd);
    TCLAP::ValueArg<long long> seed("s", "seed", "Random seed (>= 0, default 1)", false, 1, "N",
                                    cmd);
    TCLAP::ValueArg<std::string> config("c", "config",
                                        "Scenario .ini (default: share/mrpt-vslam/config/"
                                        "vslam-sim/SCENARIO.ini)",
                                        false, "", "FILE.ini", cmd);
    TCLAP::ValueArg<std::string> variant(
        "", "variant",
        "Named variant: the keys of vslam-sim/SCENARIO-NAME.ini (e.g. sports-hall-hard.ini) "
        "over the scenario's config, before --set",
        false, "", "NAME", cmd);
    TCLAP::MultiArg<std::string> sets("", "set", "Override one config key (repeatable)", false,
                                      "SECTION.KEY=VALUE", cmd);
    TCLAP::ValueArg<int> frames("n", "frames", "Simulate only the first N frames", false, -1, "N",
                                cmd);
    TCLAP::ValueArg<int> robots("r", "robots",
                                "Robots of the team (office-team: 2 or 3, default 2; "
                                "sports-hall: 1)",
                                false, -1, "N", cmd);
    TCLAP::SwitchArg no_images("", "no-images", "Do not render nor store images", cmd);
    TCLAP::SwitchArg quiet("q", "quiet", "No progress output", cmd);

    if (!cmd.parse(argc, argv)) {
        if (output.error == "One or more required arguments missing!")
            throw mrpt_vslam::core::UsageError(
                "SCENARIO and --out DIR/NAME are required (see --help)");
        if (!output.error.empty()) throw mrpt_vslam::core::UsageError(output.error);
        return std::nullopt;
    }
    if (seed.getValue() < 0) throw mrpt_vslam::core::UsageError("--seed must be >= 0");
    if (frames.isSet() && frames.getValue() <= 0)
        throw mrpt_vslam::core::UsageError("--frames must be > 0");
    if (robots.isSet() && robots.getValue() <= 0)
        throw mrpt_vslam::core::UsageError("--robots must be > 0");
    if (out.getValue().empty()) throw mrpt_vslam::core::UsageError("--out must not be empty");

    TSimCommandLine c;
    c.scenario = scenario.getValue();
    c.out_prefix = out.getValue();
    c.config_file = config.getValue();
    c.variant = variant.getValue();
    c.sets = sets.getValue();
    c.seed = static_cast<uint64_t>(seed.getValue());
    c.frames = frames.getValue();
    c.robots = robots.getValue();
    c.no_images = no_images.getValue();
    c.quiet = quiet.getValue();
    return c;
}
