#include "SimCommandLine.h"

#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt_vslam/core/TclapParse.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/core/Version.h>
#include <mrpt_vslam/sim/ScenarioFactory.h>

#include <iostream>

namespace {

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
                       mrpt_vslam::core::projectVersion());
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

    using mrpt_vslam::core::TclapOutcome;
    const auto usage_error = [](const std::string& why) {
        return mrpt_vslam::core::UsageError(why + " (see vslam-sim --help)");
    };
    std::string message;
    try {
        if (mrpt_vslam::core::parseTclap(cmd, argc, argv, "vslam-sim", message) !=
            TclapOutcome::Parsed) {
            std::cout << message;  // --help or --version
            return std::nullopt;
        }
    } catch (const mrpt_vslam::core::UsageError& e) {
        if (std::string(e.what()).rfind("One or more required arguments missing!", 0) == 0)
            throw usage_error("SCENARIO and --out DIR/NAME are required");
        throw;
    }
    if (seed.getValue() < 0) throw usage_error("--seed must be >= 0");
    if (frames.isSet() && frames.getValue() <= 0) throw usage_error("--frames must be > 0");
    if (robots.isSet() && robots.getValue() <= 0) throw usage_error("--robots must be > 0");
    if (out.getValue().empty()) throw usage_error("--out must not be empty");

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
