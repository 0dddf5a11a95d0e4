#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

/** Command line of vslam-sim. */
struct TSimCommandLine {
    std::string scenario;           ///< scenario name, e.g. sports-hall
    std::string out_prefix;         ///< --out DIR/NAME
    std::string config_file;        ///< --config FILE.ini; empty = the scenario's default
    std::string variant;            ///< --variant NAME; empty = none
    std::vector<std::string> sets;  ///< --set SECTION.KEY=VALUE, in order
    uint64_t seed = 1;              ///< --seed
    int frames = -1;                ///< --frames; −1 = the scenario's full run
    int robots = -1;                ///< --robots; −1 = the scenario's default
    bool no_images = false;         ///< --no-images
    bool quiet = false;             ///< --quiet
};

/** Parses argv. Returns nullopt when --help or --version was printed; throws core::UsageError
 *  with a one-line reason on bad arguments. */
std::optional<TSimCommandLine> parseSimCommandLine(int argc, char** argv);
