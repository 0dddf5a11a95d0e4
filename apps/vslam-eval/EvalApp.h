#pragma once

#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/LandmarkMetrics.h>
#include <mrpt_vslam/core/TrajectoryMetrics.h>
#include <mrpt_vslam/core/TumTrajectory.h>

#include <optional>

#include "EvalInputs.h"

namespace mrpt_vslam::eval {

/** One trajectory (estimate or odometry) evaluated without and with SE(2) alignment. */
struct TTrajectoryResult {
    std::string file;
    core::TumTrajectory path;
    core::TTrajectoryMetrics unaligned, aligned;
};

/** Results of one robot. */
struct TRobotResult {
    TRobotFiles files;
    core::TumTrajectory ground_truth;
    TTrajectoryResult estimate;
    std::optional<TTrajectoryResult> odometry;
};

/** Everything vslam-eval computes. */
struct TEvalResult {
    std::vector<TRobotResult> robots;
    std::optional<core::LandmarkFile> map;             ///< estimated map, when given
    std::optional<core::LandmarkFile> true_landmarks;  ///< when given
    std::optional<core::TLandmarkMetrics> landmarks;   ///< when both exist (point maps)
};

/** Evaluates a run folder or loose files against ground truth and writes metrics.json and the
 *  PNG plots (doc/data-formats.md).
 *  Usage: 1. fill `params`; 2. run(); 3. read `result` or the files in the output folder. */
class EvalApp {
  public:
    TEvalParams params;
    TEvalResult result;

    /// Loads, evaluates and writes everything; throws std::runtime_error "FILE: problem".
    void run();

    /// Loads the inputs and computes the metrics into `result` without writing files.
    void evaluate(const TEvalInputs& inputs);

  private:
    TTrajectoryResult evaluatePath(const std::string& file,
                                   const core::TumTrajectory& ground_truth) const;
};

}  // namespace mrpt_vslam::eval
