#include "ParticleFilterApp.h"

#include <mrpt_vslam/core/ConfigChoice.h>

#include <cmath>
#include <string>

namespace mrpt_vslam::apps {

ParticleFilterApp::ParticleFilterApp(core::AppArguments args, std::string name, std::string section)
    : SlamApp(std::move(args), std::move(name), std::move(section))
{
    pf.setVerbosityLevel(mrpt::system::LVL_ERROR);
}

void ParticleFilterApp::loadParticleFilterOptions(const std::string& proposals, bool adaptive)
{
    using PF = mrpt::bayes::CParticleFilter;
    constexpr const char* kSection = "ParticleFilter";
    auto& o = pf.m_options;
    try {
        // checked before MRPT's loader, which asks for the keys of the algorithm named and
        // asserts on the range with its own words
        const auto algorithm = core::readEnum(cfg, kSection, "PF_algorithm", o.PF_algorithm);
        if (algorithm != PF::pfStandardProposal && algorithm != PF::pfOptimalProposal)
            throw usageError("[ParticleFilter] PF_algorithm must be " + proposals);
        core::readEnum(cfg, kSection, "resamplingMethod", o.resamplingMethod);
        const double range =
            cfg.read_double(kSection, "max_loglikelihood_dyn_range", o.max_loglikelihood_dyn_range);
        if (!(range > 0 && std::isfinite(range)))
            throw usageError("[ParticleFilter] max_loglikelihood_dyn_range must be finite and > 0");
        o.loadFromConfigFile(cfg, kSection);
    } catch (const core::UsageError&) {
        throw;
    } catch (const std::exception& e) {
        throw configError(e);
    }
    if (o.sampleSize < 1 || o.sampleSize > kMaxParticles)
        throw usageError("[ParticleFilter] sampleSize must be 1 to " +
                         std::to_string(kMaxParticles));
    if (!(o.BETA >= 0 && o.BETA <= 1))
        throw usageError(
            "[ParticleFilter] BETA (the N_eff/N threshold of resampling) must be in "
            "[0, 1]");
    if (!(o.powFactor > 0 && o.powFactor <= 1))
        throw usageError("[ParticleFilter] powFactor must be in (0, 1]");
    if (o.adaptiveSampleSize && !adaptive)
        throw usageError("[ParticleFilter] adaptiveSampleSize is not supported (use 0)");
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
