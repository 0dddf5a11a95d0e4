#pragma once

#include <mrpt/core/bits_math.h>

#include <limits>
#include <string>
#include <vector>

namespace mrpt_vslam::mrclam {

/** Command line of mrclam2rawlog:
 *  `mrclam2rawlog DATASET_DIR --out OUT.rawlog [--robots 1,2,3] [--start S] [--end S]
 *   [--keep-ids] [--keep-robot-measurements] [--std-range M] [--std-bearing-deg D] [--quiet]`. */
struct TMrclamCommandLine {
    enum class Request { Run, ShowHelp, ShowVersion };

    Request request = Request::Run;
    std::string message;                     ///< help or version text when request != Run
    std::string dataset_dir;                 ///< DATASET_DIR with RobotN_*.dat, Barcodes.dat, ...
    std::string out_rawlog;                  ///< --out OUT.rawlog
    std::vector<int> robots{1, 2, 3, 4, 5};  ///< --robots, in the order given
    double start = 0;                        ///< [s] --start, from the dataset's first timestamp
    double end = std::numeric_limits<double>::infinity();  ///< [s] --end, same origin
    bool keep_ids = false;                    ///< --keep-ids: landmarkID = subject, else -1
    bool keep_robot_measurements = false;     ///< --keep-robot-measurements
    double std_range = 0.20;                  ///< [m] --std-range (doc/real-data.md)
    double std_bearing = mrpt::DEG2RAD(3.5);  ///< [rad] --std-bearing-deg (doc/real-data.md)
    double command_delay = 0;                 ///< [s] --command-delay (doc/real-data.md)
    bool odometry_from_ground_truth = false;  ///< --odometry-from-ground-truth (diagnostics)
    bool quiet = false;                       ///< --quiet: no summary

    /// The output prefix: out_rawlog without its `.rawlog` extension.
    std::string outPrefix() const;

    /** Parses argv without printing. Throws core::UsageError with one line ending in
     *  "(see mrclam2rawlog --help)" for an unknown option, a missing or extra argument, an
     *  output name not ending in `.rawlog`, a robot outside 1..5 or repeated, a negative or
     *  empty time window, or a non-positive standard deviation. */
    static TMrclamCommandLine parse(int argc, const char* const* argv);
};

}  // namespace mrpt_vslam::mrclam
