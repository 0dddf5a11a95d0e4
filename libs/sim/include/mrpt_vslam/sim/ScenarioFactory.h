#pragma once

#include <mrpt_vslam/sim/Scenario.h>

#include <memory>
#include <string>
#include <vector>

namespace mrpt_vslam::sim {

/// Names of all scenarios createScenario() knows.
std::vector<std::string> knownScenarios();

/// A new scenario by name; throws core::UsageError listing the known names if unknown.
std::unique_ptr<Scenario> createScenario(const std::string& name);

}  // namespace mrpt_vslam::sim
