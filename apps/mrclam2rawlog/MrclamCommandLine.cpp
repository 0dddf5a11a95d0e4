#include "MrclamCommandLine.h"

#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/core/bits_math.h>
#include <mrpt_vslam/core/EndsWith.h>
#include <mrpt_vslam/core/TclapParse.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/core/Version.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mrpt_vslam::mrclam {
namespace {

const char* const kApp = "mrclam2rawlog";

/// "1,2,3" -> {1, 2, 3}; throws a bare reason on a malformed, repeated or out-of-range number.
std::vector<int> parseRobots(const std::string& text)
{
    std::vector<int> robots;
    std::istringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        if (item.empty() || item.find_first_not_of("0123456789") != std::string::npos ||
            item.size() > 2)
            throw core::UsageError("--robots " + text + ": expected robot numbers 1..5 like 1,2,3");
        const int n = std::stoi(item);
        if (n < 1 || n > 5)
            throw core::UsageError("--robots " + text + ": unknown robot " + item +
                                   " (the dataset has robots 1..5)");
        if (std::find(robots.begin(), robots.end(), n) != robots.end())
            throw core::UsageError("--robots " + text + ": robot " + item + " given twice");
        robots.push_back(n);
    }
    if (robots.empty()) throw core::UsageError("--robots needs at least one robot");
    return robots;
}

}  // namespace

std::string TMrclamCommandLine::outPrefix() const
{
    return out_rawlog.substr(0, out_rawlog.size() - std::string(".rawlog").size());
}

TMrclamCommandLine TMrclamCommandLine::parse(int argc, const char* const* argv)
{
    TCLAP::CmdLine cmd(
        "mrclam2rawlog: converts a UTIAS MRCLAM dataset (RobotN_Odometry/Measurement/"
        "Groundtruth.dat, Landmark_Groundtruth.dat, Barcodes.dat) into an observation-only "
        "rawlog with R<n>_ODOM odometry and R<n>_RB range-bearing observations, plus TUM ground "
        "truth, dead reckoning and the landmark map beside it (see doc/real-data.md).",
        ' ', core::projectVersion());
    TCLAP::UnlabeledValueArg<std::string> dir("DATASET_DIR", "Folder of the dataset's .dat files",
                                              true, "", "DATASET_DIR", cmd);
    TCLAP::ValueArg<std::string> out("o", "out",
                                     "Output rawlog OUT.rawlog; OUT.groundtruth_R<n>.tum, "
                                     "OUT.odometry_R<n>.tum, OUT.landmarks.txt beside it",
                                     true, "", "OUT.rawlog", cmd);
    TCLAP::ValueArg<std::string> robots("r", "robots", "Robots to import (default 1,2,3,4,5)",
                                        false, "1,2,3,4,5", "N,N,...", cmd);
    TCLAP::ValueArg<double> start("", "start",
                                  "Start of the time window [s] after the first timestamp of the "
                                  "chosen robots' files (default 0)",
                                  false, 0, "S", cmd);
    TCLAP::ValueArg<double> end("", "end",
                                "End of the time window [s], same origin (default: "
                                "the whole dataset)",
                                false, 0, "S", cmd);
    TCLAP::SwitchArg keep_ids("", "keep-ids",
                              "landmarkID = subject number (default -1: identities hidden)", cmd);
    TCLAP::SwitchArg keep_robots(
        "", "keep-robot-measurements",
        "Keep the readings of the other imported robots' barcodes, as R<n>_ROBOTS with "
        "landmarkID = the seen robot (dropped by default)",
        cmd);
    TCLAP::ValueArg<double> std_range("", "std-range",
                                      "sensor_std_range of the observations [m] (default 0.20)",
                                      false, 0.20, "M", cmd);
    TCLAP::ValueArg<double> std_bearing("", "std-bearing-deg",
                                        "sensor_std_yaw of the observations [deg] (default 3.5)",
                                        false, 3.5, "D", cmd);
    TCLAP::ValueArg<double> command_delay(
        "", "command-delay",
        "Integrate each speed command this much later [s] (default 0; the robots of dataset 7 "
        "follow their commands about 0.2 s late)",
        false, 0, "S", cmd);
    TCLAP::SwitchArg odometry_from_ground_truth(
        "", "odometry-from-ground-truth",
        "R<n>_ODOM holds the Vicon poses (where Vicon has none, the last one carried on by the "
        "commands): mapping with known poses, for diagnostics",
        cmd);
    TCLAP::SwitchArg quiet("q", "quiet", "No summary on stdout", cmd);

    TMrclamCommandLine c;
    const core::TclapOutcome outcome = core::parseTclap(cmd, argc, argv, kApp, c.message);
    if (outcome == core::TclapOutcome::ShowHelp) {
        c.request = Request::ShowHelp;
        return c;
    }
    if (outcome == core::TclapOutcome::ShowVersion) {
        c.request = Request::ShowVersion;
        return c;
    }
    const auto usage_error = [](const std::string& why) {
        return core::UsageError(why + " (see " + kApp + " --help)");
    };
    c.dataset_dir = dir.getValue();
    c.out_rawlog = out.getValue();
    const std::string ext = ".rawlog";
    if (c.out_rawlog.size() <= ext.size() || !core::endsWith(c.out_rawlog, ext) ||
        c.out_rawlog[c.out_rawlog.size() - ext.size() - 1] == '/')
        throw usage_error("--out " + c.out_rawlog + ": expected a file name ending in .rawlog");
    try {
        c.robots = parseRobots(robots.getValue());
    } catch (const core::UsageError& e) {
        throw usage_error(e.what());
    }
    c.start = start.getValue();
    if (end.isSet()) c.end = end.getValue();
    if (!(c.start >= 0)) throw usage_error("--start must be >= 0");
    if (!(c.start < c.end)) throw usage_error("--start must be before --end");
    c.keep_ids = keep_ids.getValue();
    c.keep_robot_measurements = keep_robots.getValue();
    c.std_range = std_range.getValue();
    c.std_bearing = mrpt::DEG2RAD(std_bearing.getValue());
    if (!(c.std_range > 0 && std::isfinite(c.std_range)))
        throw usage_error("--std-range must be > 0");
    if (!(c.std_bearing > 0 && std::isfinite(c.std_bearing)))
        throw usage_error("--std-bearing-deg must be > 0");
    c.command_delay = command_delay.getValue();
    if (!(std::abs(c.command_delay) <= 5))
        throw usage_error("--command-delay must be within +-5 s");
    c.odometry_from_ground_truth = odometry_from_ground_truth.getValue();
    c.quiet = quiet.getValue();
    return c;
}

}  // namespace mrpt_vslam::mrclam
