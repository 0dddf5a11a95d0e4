#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/OfficeTeamScenario.h>
#include <mrpt_vslam/sim/OmniViewsScenario.h>
#include <mrpt_vslam/sim/ScenarioFactory.h>
#include <mrpt_vslam/sim/SportsHallScenario.h>

namespace mrpt_vslam::sim {

std::vector<std::string> knownScenarios() { return {"sports-hall", "office-team", "omni-views"}; }

std::unique_ptr<Scenario> createScenario(const std::string& name)
{
    if (name == "sports-hall") return std::make_unique<SportsHallScenario>();
    if (name == "office-team") return std::make_unique<OfficeTeamScenario>();
    if (name == "omni-views") return std::make_unique<OmniViewsScenario>();
    std::string known;
    for (const std::string& n : knownScenarios()) known += (known.empty() ? "" : ", ") + n;
    throw core::UsageError("unknown scenario '" + name + "' (known: " + known + ")");
}

}  // namespace mrpt_vslam::sim
