#pragma once

#include <string>

#include "EvalApp.h"

namespace mrpt_vslam::eval {

/** Writes metrics.json (fields in doc/data-formats.md) atomically. */
void writeMetricsJson(const TEvalResult& result, const TEvalInputs& inputs,
                      const TEvalParams& params, const std::string& file);

}  // namespace mrpt_vslam::eval
