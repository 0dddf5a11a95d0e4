#include "ParticleFilterApp.h"

#include <cmath>
#include <string>

namespace mrpt_vslam::apps {

ParticleFilterApp::ParticleFilterApp(core::AppArguments args, std::string name, std::string section)
    : SlamApp(std::move(args), std::move(name), std::move(section))
{
    pf.setVerbosityLevel(mrpt::system::LVL_ERROR);
}

void ParticleFilterApp::checkParticleFilterOptions(const std::string& proposals,
                                                   bool adaptive) const
{
    const auto& o = pf.m_options;
    if (o.sampleSize < 1 || o.sampleSize > kMaxParticles)
        throw usageError("[ParticleFilter] sampleSize must be 1 to " +
                         std::to_string(kMaxParticles));
    if (!(o.BETA >= 0 && o.BETA <= 1))
        throw usageError(
            "[ParticleFilter] BETA (the N_eff/N threshold of resampling) must be in "
            "[0, 1]");
    if (!(o.powFactor > 0 && o.powFactor <= 1))
        throw usageError("[ParticleFilter] powFactor must be in (0, 1]");
    if (!(o.max_loglikelihood_dyn_range > 0 && std::isfinite(o.max_loglikelihood_dyn_range)))
        throw usageError("[ParticleFilter] max_loglikelihood_dyn_range must be finite and > 0");
    if (o.adaptiveSampleSize && !adaptive)
        throw usageError("[ParticleFilter] adaptiveSampleSize is not supported (use 0)");
    using PF = mrpt::bayes::CParticleFilter;
    if (o.PF_algorithm != PF::pfStandardProposal && o.PF_algorithm != PF::pfOptimalProposal)
        throw usageError("[ParticleFilter] PF_algorithm must be " + proposals);
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
