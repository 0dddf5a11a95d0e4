#pragma once

#include <string>
#include <vector>

namespace mrpt_vslam::multirobot {

/** Command line of stereo-frontend:
 *  `stereo-frontend CONFIG.ini INPUT.rawlog --out DIR/NAME [--quiet] [--help] [--version]`. */
struct TFrontEndCommandLine {
    enum class Request { Run, ShowHelp, ShowVersion };

    Request request = Request::Run;
    std::string message;      ///< help or version text when request != Run
    std::string config_file;  ///< CONFIG.ini (only its [StereoFrontEnd] section is read)
    std::string input;        ///< INPUT.rawlog
    std::string out_prefix;  ///< --out DIR/NAME: writes DIR/NAME.rawlog and DIR/NAME.<ground truth>
    bool quiet = false;      ///< --quiet: no progress line and no summary

    /** Parses argv without printing. Throws core::UsageError with one line ending in
     *  "(see stereo-frontend --help)" for an unknown option, a missing or extra argument, or a
     *  missing --out value. */
    static TFrontEndCommandLine parse(int argc, const char* const* argv);
};

}  // namespace mrpt_vslam::multirobot
