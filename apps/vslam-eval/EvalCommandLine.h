#pragma once

#include <mrpt_vslam/core/EvalInputs.h>

#include <optional>

namespace mrpt_vslam::eval {

/** Parses the command line of vslam-eval. Returns nullopt after printing --help or --version;
 *  throws core::UsageError "vslam-eval: problem (see vslam-eval --help)" on a bad command line. */
std::optional<core::TEvalParams> parseEvalCommandLine(int argc, char** argv);

}  // namespace mrpt_vslam::eval
