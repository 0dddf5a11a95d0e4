#include "SimConfig.h"

#include <mrpt_vslam/core/UsageError.h>

#include <filesystem>

std::string shippedSimConfig(const std::string& name)
{
    const std::string relative = "/vslam-sim/" + name + ".ini";
    for (const std::string dir : {MRPT_VSLAM_CONFIG_SOURCE_DIR, MRPT_VSLAM_CONFIG_INSTALL_DIR})
        if (std::filesystem::is_regular_file(dir + relative)) return dir + relative;
    throw mrpt_vslam::core::UsageError("no config vslam-sim/" + name +
                                       ".ini (looked for " MRPT_VSLAM_CONFIG_SOURCE_DIR + relative +
                                       " and " MRPT_VSLAM_CONFIG_INSTALL_DIR + relative + ")");
}

void loadSimConfig(const std::string& file, const std::string& variant_file,
                   const std::vector<std::string>& sets, mrpt_vslam::core::CheckedConfigFile& cfg)
{
    std::vector<mrpt_vslam::core::TConfigOverride> overrides;
    if (!variant_file.empty()) {
        mrpt_vslam::core::CheckedConfigFile variant;
        variant.loadFile(variant_file);
        std::vector<std::string> sections, keys;
        variant.getAllSections(sections);
        for (const std::string& section : sections) {
            variant.getAllKeys(section, keys);
            for (const std::string& key : keys)
                overrides.push_back({section, key, variant.read_string(section, key, "")});
        }
    }
    for (const std::string& set : sets)
        overrides.push_back(mrpt_vslam::core::TConfigOverride::parse(set));
    cfg.loadFile(file, overrides);
}
