#pragma once

#include <stdexcept>

namespace mrpt_vslam::core {

/** A run that was asked for wrongly: a bad command line or a bad configuration (missing file,
 *  unknown key, malformed `--set`). A driver app prints what() and exits with code 2; every
 *  other std::exception means a runtime failure and exit code 1 (see doc/app-conventions.md). */
class UsageError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace mrpt_vslam::core
