#pragma once

#include <mrpt_vslam/core/CheckedConfigFile.h>

#include <string>
#include <vector>

/** The default .ini of a scenario: `vslam-sim/SCENARIO.ini` under the source tree's
 *  share/mrpt-vslam/config, else under the installed share directory. Throws core::UsageError
 *  if neither exists. */
std::string defaultScenarioConfig(const std::string& scenario);

/** Loads `file` with the `SECTION.KEY=VALUE` overrides into `cfg`, which then reports keys that
 *  nothing read (typos) through throwIfUnreadKeys(). Throws core::UsageError. */
void loadSimConfig(const std::string& file, const std::vector<std::string>& sets,
                   mrpt_vslam::core::CheckedConfigFile& cfg);
