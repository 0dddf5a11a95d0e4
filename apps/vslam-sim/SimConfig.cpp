#include "SimConfig.h"

#include <mrpt_vslam/core/UsageError.h>

#include <filesystem>

std::string defaultScenarioConfig(const std::string& scenario)
{
    const std::string relative = "/vslam-sim/" + scenario + ".ini";
    for (const std::string dir : {MRPT_VSLAM_CONFIG_SOURCE_DIR, MRPT_VSLAM_CONFIG_INSTALL_DIR})
        if (std::filesystem::is_regular_file(dir + relative)) return dir + relative;
    throw mrpt_vslam::core::UsageError("no default config for scenario '" + scenario +
                                       "' (looked for " MRPT_VSLAM_CONFIG_SOURCE_DIR + relative +
                                       " and " MRPT_VSLAM_CONFIG_INSTALL_DIR + relative +
                                       "); use --config");
}

void loadSimConfig(const std::string& file, const std::vector<std::string>& sets,
                   mrpt_vslam::core::CheckedConfigFile& cfg)
{
    std::vector<mrpt_vslam::core::TConfigOverride> overrides;
    for (const std::string& set : sets)
        overrides.push_back(mrpt_vslam::core::TConfigOverride::parse(set));
    cfg.loadFile(file, overrides);
}
