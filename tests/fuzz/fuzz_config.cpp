// The three driver apps' configuration on any text: the .ini reader, the `--set` parser and
// every option loader, as initialize() runs them. Lines "--set S.K=V" of the input are given as
// overrides, the rest is the .ini file; the rawlog does not exist, so a configuration that
// passes ends in "cannot open rawlog" without reading data. Errors are exceptions; a crash or a
// hang is a bug.
#include <mrpt_vslam/apps/MultiRobotVSLAMApp.h>
#include <mrpt_vslam/apps/OmniFastSLAMApp.h>
#include <mrpt_vslam/apps/ViewSLAMApp.h>
#include <mrpt_vslam/core/AppArguments.h>

#include <cstdint>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include "FuzzInput.h"

namespace {
template <class APP>
void initialize(const std::string& name, const std::vector<std::string>& argv_text)
{
    std::vector<const char*> argv{name.c_str()};
    for (const auto& a : argv_text) argv.push_back(a.c_str());
    try {
        APP app(mrpt_vslam::core::AppArguments::parse(static_cast<int>(argv.size()), argv.data(),
                                                      name, ""));
        app.initialize();
    } catch (const std::exception&) {
    }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace mrpt_vslam;
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    std::string ini;
    std::vector<std::string> argv;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("--set ", 0) == 0) {
            argv.push_back("--set");
            argv.push_back(line.substr(6));
        } else {
            ini += line + "\n";
        }
    }
    const std::string config = fuzz::writeScratchFile(
        "input.ini", reinterpret_cast<const uint8_t*>(ini.data()), ini.size());
    argv.insert(argv.begin(), {config, fuzz::scratchFolder() + "/missing.rawlog", "--quiet"});
    initialize<apps::OmniFastSLAMApp>("omni-fastslam", argv);
    initialize<apps::MultiRobotVSLAMApp>("multirobot-vslam", argv);
    initialize<apps::ViewSLAMApp>("view-slam", argv);
    return 0;
}
