#pragma once

#include <mrpt_vslam/core/RunEvaluation.h>

#include <string>

namespace mrpt_vslam::core {

/** Writes metrics.json (fields in doc/data-formats.md) atomically. */
void writeMetricsJson(const TEvalResult& result, const TEvalInputs& inputs,
                      const TEvalParams& params, const std::string& file);

}  // namespace mrpt_vslam::core
