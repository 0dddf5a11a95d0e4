#pragma once

#include <mrpt_vslam/core/CheckedConfigFile.h>

#include <string>
#include <vector>

/** A shipped .ini of vslam-sim: `vslam-sim/NAME.ini` under the source tree's
 *  share/mrpt-vslam/config, else under the installed share directory (NAME: a scenario, or
 *  SCENARIO-VARIANT). Throws core::UsageError if neither exists. */
std::string shippedSimConfig(const std::string& name);

/** Loads `file` into `cfg` with, in this order, every key of `variant_file` (if not empty) and
 *  the `SECTION.KEY=VALUE` overrides `sets`; `cfg` then reports keys that nothing read (typos,
 *  and a variant's keys the scenario does not have) through throwIfUnreadKeys(). Throws
 *  core::UsageError. */
void loadSimConfig(const std::string& file, const std::string& variant_file,
                   const std::vector<std::string>& sets, mrpt_vslam::core::CheckedConfigFile& cfg);
