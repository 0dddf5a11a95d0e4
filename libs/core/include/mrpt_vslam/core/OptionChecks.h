#pragma once

#include <string>
#include <string_view>

namespace mrpt_vslam::core {

/** Checks of options: each throws std::invalid_argument unless `ok`, with a message naming the
 *  key, which the apps print as the run's one-line error (doc/app-conventions.md). */

/// "[SECTION] KEY: WHAT": a configuration key checked as it is read
void requireKey(bool ok, const std::string& section, std::string_view key, std::string_view what);

/// "KEY WHAT": an option checked where its section is not known (its reader puts it in front)
void requireOption(bool ok, std::string_view key, std::string_view what);

/// "OWNER: KEY = VALUE REQUIREMENT" (VALUE as %g): a class's parameter, with the value it has
void requireParameter(bool ok, std::string_view owner, std::string_view key, double value,
                      std::string_view requirement);

}  // namespace mrpt_vslam::core
