#include "ParticleFilterApp.h"

#include <mrpt_vslam/core/ParticleFilterOptions.h>

#include <cmath>
#include <sstream>
#include <string>

namespace mrpt_vslam::apps {

ParticleFilterApp::ParticleFilterApp(core::AppArguments args, std::string name, std::string section)
    : SlamApp(std::move(args), std::move(name), std::move(section))
{
    pf.setVerbosityLevel(mrpt::system::LVL_ERROR);
}

void ParticleFilterApp::loadParticleFilterOptions(bool adaptive)
{
    try {
        core::loadParticleFilterOptions(cfg, "ParticleFilter", pf.m_options);
    } catch (const std::exception& e) {
        throw configError(e);
    }
    const auto& o = pf.m_options;
    if (o.sampleSize < 1 || o.sampleSize > kMaxParticles)
        throw usageError("[ParticleFilter] sampleSize must be 1 to " +
                         std::to_string(kMaxParticles));
    if (o.adaptiveSampleSize && !adaptive)
        throw usageError("[ParticleFilter] adaptiveSampleSize is not supported (use false)");
}

size_t ParticleFilterApp::loadFilterRuns(size_t runs, bool smoothing,
                                         const std::string& smoothingKey) const
{
    const int n = cfg.read_int(ownSection(), "filter_runs", static_cast<int>(runs));
    if (n < 1 || n > 64)
        throw usageError(ownKey("filter_runs") + " must be an integer from 1 to 64");
    if (n > 1 && !smoothing)
        throw usageError(ownKey("filter_runs") + " > 1 needs " + smoothingKey +
                         " = true (runs are compared by their smoothed cost)");
    return static_cast<size_t>(n);
}

void ParticleFilterApp::reportFilterRuns(const std::vector<TRunOutcome>& outcomes, size_t kept,
                                         core::RunReport& report) const
{
    if (outcomes.size() < 2) return;
    std::ostringstream j;
    j.precision(17);  // the costs as compared
    for (size_t i = 0; i < outcomes.size(); i++)
        j << (i ? ", " : "[") << "{\"seed\": " << seed + i
          << ", \"smoothing_cost\": " << outcomes[i].cost
          << ", \"landmarks\": " << outcomes[i].landmarks
          << ", \"readings\": " << outcomes[i].readings << "}";
    report.setResultJson("filter_runs", j.str() + "]");
    report.setCount("kept_seed", static_cast<double>(seed + kept));
}

void ParticleFilterApp::filterStep(const mrpt::obs::CActionCollection& actions,
                                   const mrpt::obs::CSensoryFrame& frame, core::RunTimer& timer)
{
    timedStep(timer, "step " + std::to_string(steps), [&] {
        auto& global = mrpt::random::getRandomGenerator();
        for (auto& f : m_stepped) {
            global = f.resampling;
            pf.executeOn(*f.filter, &actions, &frame);
            f.resampling = global;
        }
    });
}

}  // namespace mrpt_vslam::apps
