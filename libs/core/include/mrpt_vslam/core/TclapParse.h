#pragma once

#include <string>

namespace TCLAP {
class CmdLine;
}

namespace mrpt_vslam::core {

/// What a command line asked for.
enum class TclapOutcome { Parsed, ShowHelp, ShowVersion };

/** Parses argv with `cmd` (already given its arguments) without printing anything:
 *  - `--help` returns ShowHelp with TCLAP's usage text in `message`; `--version` returns
 *    ShowVersion with versionLine() of `app_name` in `message`: what the app prints on stdout;
 *  - an unknown option (TCLAP would take "--qiet" as a positional) or any parse error throws
 *    UsageError "reason (see APP --help)".
 *  Replaces the output object of `cmd` with one that lives only during the call. */
TclapOutcome parseTclap(TCLAP::CmdLine& cmd, int argc, const char* const* argv,
                        const std::string& app_name, std::string& message);

}  // namespace mrpt_vslam::core
