#pragma once

#include <string>

namespace mrpt_vslam::core {

/** Version of this project, "MAJOR.MINOR.PATCH" (CMake's PROJECT_VERSION). */
std::string projectVersion();

/** Version of the MRPT libraries the program runs with, e.g. "2.5.8". */
std::string mrptVersion();

/** What `APP --version` prints: "APP VERSION (MRPT x.y.z)" and a newline. */
std::string versionLine(const std::string& app);

}  // namespace mrpt_vslam::core
