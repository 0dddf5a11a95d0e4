#pragma once

#include <limits>
#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** Command-line parameters of vslam-eval (see README.md). */
struct TEvalParams {
    std::string run_dir;           ///< run folder, or empty with `estimate_file`
    std::string estimate_file;     ///< loose estimate TUM file
    std::string odometry_file;     ///< loose odometry TUM file (optional)
    std::string ground_truth;      ///< `NAME.rawlog`, prefix `NAME`, or a TUM file
    std::string landmarks_gt;      ///< true landmarks file (optional; overrides NAME.landmarks.txt)
    std::string map_file;          ///< estimated map (optional; default RUN_DIR/map.txt)
    std::string out_dir;           ///< where metrics.json and the plots go (default RUN_DIR)
    double landmark_cutoff = 1.5;  ///< [m]
    double time_tolerance = 0.05;  ///< [s]
    double heading_threshold_deg = 5;  ///< [deg]
    /// [s] only the estimated poses later than this (--after; default: all)
    double after = -std::numeric_limits<double>::infinity();
    bool align = false;  ///< plots show the SE(2)-aligned estimate (the JSON always has both)
};

/** The files of one robot. `robot` is empty for single-robot runs. */
struct TRobotFiles {
    std::string robot;
    std::string estimate, odometry, ground_truth;  ///< odometry may be empty
};

/** Every file an evaluation reads and the folder it writes to. */
struct TEvalInputs {
    std::vector<TRobotFiles> robots;
    std::string map_file;      ///< empty when there is no map
    std::string landmarks_gt;  ///< empty when there are no true landmarks
    std::string out_dir;
};

/** The prefix NAME of the ground-truth files (doc/data-formats.md, "Ground truth") that `name`
 *  stands for: a rawlog `NAME.rawlog` or `NAME.rawlog.gz`, a trajectory `NAME.groundtruth.tum`
 *  (extensions in any case), or NAME itself. */
std::string groundTruthPrefixOf(const std::string& name);

/** The ground-truth file of `robot` for the prefix NAME: NAME.groundtruth.tum for a
 *  single-robot run (`robot` empty), else NAME.groundtruth_<robot>.tum, or, for the only robot
 *  of a run (`only_robot`) when that file does not exist, NAME.groundtruth.tum. */
std::string groundTruthFileOf(const std::string& prefix, const std::string& robot, bool only_robot);

/** Finds the files to evaluate from the parameters: estimates in the run folder, ground truth
 *  from `--ground-truth` or run.json. Throws std::runtime_error "FILE: problem" (also for a run
 *  folder whose run.json says the run did not complete), or UsageError
 *  when neither a run folder nor an estimate is given, or an estimate without an output folder. */
TEvalInputs resolveInputs(const TEvalParams& params);

}  // namespace mrpt_vslam::core
