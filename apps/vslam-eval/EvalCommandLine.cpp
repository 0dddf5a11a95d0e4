#include "EvalCommandLine.h"

#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt_vslam/core/TclapParse.h>
#include <mrpt_vslam/core/Version.h>

#include <iostream>
#include <limits>

namespace mrpt_vslam::eval {

std::optional<core::TEvalParams> parseEvalCommandLine(int argc, char** argv)
{
    TCLAP::CmdLine cmd(
        "vslam-eval: trajectory and map metrics of a SLAM run against ground truth, with PNG "
        "plots.\n"
        "  vslam-eval RUN_DIR [--ground-truth NAME|NAME.rawlog|GT.tum] [--out DIR]\n"
        "  vslam-eval --estimate EST.tum --ground-truth GT.tum [--landmarks-gt L.txt] "
        "[--map map.txt] --out DIR",
        ' ', core::projectVersion());
    TCLAP::UnlabeledValueArg<std::string> runDir(
        "RUN_DIR", "Run folder with estimated_path*.tum [odometry_path*.tum, map.txt, run.json]",
        false, "", "RUN_DIR", cmd);
    TCLAP::ValueArg<std::string> estimate("", "estimate",
                                          "Estimated trajectory (TUM), instead of RUN_DIR", false,
                                          "", "FILE.tum", cmd);
    TCLAP::ValueArg<std::string> odometry(
        "", "odometry", "Odometry trajectory (TUM) with --estimate", false, "", "FILE.tum", cmd);
    TCLAP::ValueArg<std::string> groundTruth(
        "", "ground-truth",
        "Ground truth: rawlog NAME.rawlog, prefix NAME or NAME.groundtruth.tum (uses "
        "NAME.groundtruth[_<ROBOT>].tum and NAME.landmarks.txt), or a TUM file. Default: "
        "\"ground_truth\" of RUN_DIR/run.json",
        false, "", "NAME|FILE", cmd);
    TCLAP::ValueArg<std::string> landmarksGt(
        "", "landmarks-gt", "True landmarks (x y z or id x y z)", false, "", "FILE", cmd);
    TCLAP::ValueArg<std::string> map("", "map", "Estimated map (default RUN_DIR/map.txt)", false,
                                     "", "FILE", cmd);
    TCLAP::ValueArg<std::string> out("", "out", "Output folder (default RUN_DIR)", false, "", "DIR",
                                     cmd);
    TCLAP::ValueArg<double> cutoff("", "landmark-cutoff", "Max distance of a landmark match [m]",
                                   false, 1.5, "M", cmd);
    TCLAP::ValueArg<double> tolerance("", "time-tolerance",
                                      "Max time difference of an estimate/ground-truth pair [s]",
                                      false, 0.05, "S", cmd);
    TCLAP::ValueArg<double> heading("", "heading-threshold-deg",
                                    "Threshold of the share of frames with a small heading error",
                                    false, 5.0, "DEG", cmd);
    TCLAP::ValueArg<double> after(
        "", "after",
        "Evaluate only the estimated poses later than this time [s] (e.g. after a gap in a live "
        "run's stream; run.json's results.team_link.robots.<ROBOT>.late_until)",
        false, -std::numeric_limits<double>::infinity(), "T", cmd);
    TCLAP::SwitchArg align("", "align",
                           "Plot the SE(2)-aligned estimate (metrics.json always has both)", cmd);
    std::string message;
    if (core::parseTclap(cmd, argc, argv, "vslam-eval", message) != core::TclapOutcome::Parsed) {
        std::cout << message;  // --help or --version
        return std::nullopt;
    }
    core::TEvalParams p;
    p.run_dir = runDir.getValue();
    p.estimate_file = estimate.getValue();
    p.odometry_file = odometry.getValue();
    p.ground_truth = groundTruth.getValue();
    p.landmarks_gt = landmarksGt.getValue();
    p.map_file = map.getValue();
    p.out_dir = out.getValue();
    p.landmark_cutoff = cutoff.getValue();
    p.time_tolerance = tolerance.getValue();
    p.heading_threshold_deg = heading.getValue();
    p.after = after.getValue();
    p.align = align.getValue();
    return p;
}

}  // namespace mrpt_vslam::eval
