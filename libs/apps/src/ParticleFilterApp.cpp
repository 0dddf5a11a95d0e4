#include "ParticleFilterApp.h"

#include <mrpt_vslam/core/ParticleFilterOptions.h>

#include <cmath>
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
