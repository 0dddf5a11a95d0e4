#include "FrontEndCommandLine.h"

#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/core/Version.h>

namespace mrpt_vslam::multirobot {
namespace {

const char* const kHelp =
    "stereo-frontend: stereo front-end of the multi-robot visual SLAM (Gil et al. 2010).\n"
    "Turns every CObservationStereoImages of a rawlog (label <ROBOT>_STEREO or any other)\n"
    "into a CObservationVisualLandmarks labelled <ROBOT>_LANDMARKS (LABEL_LANDMARKS for\n"
    "another label LABEL; Harris corners, stereo correspondence,\n"
    "U-SURF descriptors, points tracked over consecutive frames); every other entry is\n"
    "copied unchanged and in order. Ground-truth files beside the input are copied.\n"
    "\n"
    "Usage: stereo-frontend CONFIG.ini INPUT.rawlog --out DIR/NAME [--quiet]\n"
    "\n"
    "  CONFIG.ini       configuration; only its [StereoFrontEnd] section is read\n"
    "  INPUT.rawlog     rawlog with CObservationStereoImages (images may be in\n"
    "                   INPUT_Images/)\n"
    "  --out DIR/NAME   writes DIR/NAME.rawlog and copies INPUT.groundtruth*.tum,\n"
    "                   INPUT.odometry*.tum and INPUT.landmarks.txt to DIR/NAME.*\n"
    "  -q, --quiet      no progress line and no summary\n"
    "  -h, --help       prints this text\n"
    "  --version        prints the version\n"
    "\n"
    "Exit codes: 0 success, 1 runtime error, 2 usage or configuration error.\n";

}  // namespace

TFrontEndCommandLine TFrontEndCommandLine::parse(int argc, const char* const* argv)
{
    const auto usage_error = [](const std::string& why) {
        return core::UsageError(why + " (see stereo-frontend --help)");
    };
    TFrontEndCommandLine c;
    std::vector<std::string> positionals;
    bool out_given = false;
    for (int i = 1; i < argc; i++) {
        const std::string word = argv[i];
        if (word == "-h" || word == "--help") {
            c.request = Request::ShowHelp;
            c.message = kHelp;
            return c;
        }
        if (word == "--version") {
            c.request = Request::ShowVersion;
            c.message = core::versionLine("stereo-frontend");
            return c;
        }
        if (word == "-q" || word == "--quiet") {
            c.quiet = true;
        } else if (word == "--out") {
            if (i + 1 == argc) throw usage_error("--out needs DIR/NAME");
            c.out_prefix = argv[++i];
            out_given = true;
        } else if (word.rfind("--out=", 0) == 0) {
            c.out_prefix = word.substr(6);
            out_given = true;
        } else if (word.size() > 1 && word[0] == '-') {
            throw usage_error("unknown option " + word);
        } else {
            positionals.push_back(word);
        }
    }
    if (positionals.size() < 2) throw usage_error("CONFIG.ini and INPUT.rawlog are required");
    if (positionals.size() > 2) throw usage_error("unexpected argument " + positionals[2]);
    if (!out_given) throw usage_error("--out DIR/NAME is required");
    if (c.out_prefix.empty() || c.out_prefix.back() == '/')
        throw usage_error("--out needs DIR/NAME, not a folder");
    c.config_file = positionals[0];
    c.input = positionals[1];
    return c;
}

}  // namespace mrpt_vslam::multirobot
