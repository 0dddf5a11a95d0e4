#pragma once

#include <string>

#include "EvalApp.h"

namespace mrpt_vslam::eval {

/** XY paths (ground truth, odometry, estimate) with true and estimated landmarks, equal aspect.
 *  With `aligned`, each path is drawn after its own SE(2) alignment to the ground truth, and the
 *  map after the estimate's (single robot). */
void plotPaths(const core::TEvalResult& result, bool aligned, const std::string& file);

/** Position and heading error over time, estimate vs odometry. */
void plotErrors(const core::TEvalResult& result, bool aligned, const std::string& file);

/** One bar per true landmark: error of its matched estimate; missed ones marked. */
void plotLandmarkErrors(const core::TLandmarkMetrics& metrics, const std::string& file);

}  // namespace mrpt_vslam::eval
