#pragma once

#include <mrpt_vslam/core/EvalInputs.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/LandmarkMetrics.h>
#include <mrpt_vslam/core/TrajectoryMetrics.h>
#include <mrpt_vslam/core/TumTrajectory.h>

#include <optional>
#include <ostream>

namespace mrpt_vslam::core {

/** One trajectory (estimate or odometry) evaluated without and with SE(2) alignment. */
struct TTrajectoryResult {
    std::string file;
    TumTrajectory path;
    TTrajectoryMetrics unaligned, aligned;
};

/** Results of one robot. */
struct TRobotResult {
    TRobotFiles files;
    TumTrajectory ground_truth;
    TTrajectoryResult estimate;
    std::optional<TTrajectoryResult> odometry;
};

/** Everything vslam-eval computes. */
struct TEvalResult {
    std::vector<TRobotResult> robots;
    std::optional<LandmarkFile> map;             ///< estimated map, when given
    std::optional<LandmarkFile> true_landmarks;  ///< when given
    std::optional<TLandmarkMetrics> landmarks;   ///< when both exist (point maps)
};

/** Evaluates estimates against ground truth (doc/data-formats.md, "metrics.json"): every driver
 *  app calls it on its run folder, and vslam-eval on any folder or loose files.
 *  \throw std::runtime_error "FILE: problem" on unreadable or unmatched inputs. */
TEvalResult evaluateRun(const TEvalInputs& inputs, const TEvalParams& params);

/** resolveInputs(), evaluateRun() and writeMetricsJson() into `<out_dir>/metrics.json`.
 *  Throws UsageError for a parameter out of its range. */
TEvalResult evaluateRunFolder(const TEvalParams& params);

/** `result` for people: one line per trajectory (estimate, SE(2)-aligned estimate, odometry) and
 *  one for the landmarks. vslam-eval prints it, and the driver apps at the end of a run. */
void printEvalSummary(std::ostream& os, const TEvalResult& result);

}  // namespace mrpt_vslam::core
