#pragma once

#include <mrpt_vslam/core/RunEvaluation.h>

namespace mrpt_vslam::eval {

/** vslam-eval: evaluates a run folder or loose files against ground truth and writes
 *  metrics.json (core::evaluateRun) and the PNG plots (doc/data-formats.md).
 *  Usage: 1. fill `params`; 2. run(); 3. read `result` or the files in the output folder. */
class EvalApp {
  public:
    core::TEvalParams params;
    core::TEvalResult result;
    /// Loads, evaluates and writes everything, and prints core::printEvalSummary(); throws
    /// std::runtime_error "FILE: problem".
    void run();
};

}  // namespace mrpt_vslam::eval
