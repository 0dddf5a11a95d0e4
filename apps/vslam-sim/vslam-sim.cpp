// vslam-sim: simulates a scenario and writes its dataset (see doc/simulator.md).
#include <mrpt/system/CTicTac.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/ScenarioFactory.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <iostream>

#include "SimCommandLine.h"
#include "SimConfig.h"

namespace {

/// On a terminal one line updated in place; otherwise a line every 10 % of the frames.
void printProgress(const std::string& scenario, int done, int total)
{
    static const bool tty = isatty(fileno(stderr)) != 0;
    if (tty) {
        std::fprintf(stderr, "\rvslam-sim: %s frame %d/%d", scenario.c_str(), done, total);
        if (done == total) std::fputc('\n', stderr);
    } else if (done == total || done % std::max(1, total / 10) == 0) {
        std::fprintf(stderr, "vslam-sim: %s frame %d/%d\n", scenario.c_str(), done, total);
    }
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        const std::optional<TSimCommandLine> cli = parseSimCommandLine(argc, argv);
        if (!cli) return 0;  // --help or --version

        auto scenario = mrpt_vslam::sim::createScenario(cli->scenario);
        const std::string config_file =
            cli->config_file.empty() ? shippedSimConfig(cli->scenario) : cli->config_file;
        const std::string variant_file =
            cli->variant.empty() ? "" : shippedSimConfig(cli->scenario + "-" + cli->variant);
        mrpt_vslam::core::CheckedConfigFile cfg;
        loadSimConfig(config_file, variant_file, cli->sets, cfg);
        scenario->loadConfig(cfg);
        cfg.throwIfUnreadKeys();

        mrpt_vslam::sim::TSimulationOptions opts;
        opts.out_prefix = cli->out_prefix;
        opts.seed = cli->seed;
        opts.frames = cli->frames;
        opts.robots = cli->robots;
        opts.write_images = !cli->no_images;
        if (!cli->quiet)
            opts.on_progress = [&](int done, int total) {
                printProgress(cli->scenario, done, total);
            };

        mrpt::system::CTicTac timer;
        const mrpt_vslam::sim::TSimulationSummary s = scenario->run(opts);
        if (!cli->quiet) {
            const std::string team =
                s.robots > 1 ? ", " + std::to_string(s.robots) + " robots" : std::string();
            std::fprintf(stderr,
                         "vslam-sim: wrote %s.rawlog: %d frames%s, %s, path %.1f m, "
                         "seed %llu, %.1f s\n",
                         opts.out_prefix.c_str(), s.frames, team.c_str(), s.details.c_str(),
                         s.path_length, static_cast<unsigned long long>(opts.seed), timer.Tac());
        }
        return 0;
    } catch (const mrpt_vslam::core::UsageError& e) {
        std::cerr << "vslam-sim: error: " << mrpt_vslam::core::oneLineMessage(e) << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "vslam-sim: error: " << mrpt_vslam::core::oneLineMessage(e) << "\n";
        return 1;
    }
}
