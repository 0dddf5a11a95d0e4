#include <mrpt_vslam/core/ConfigChoice.h>
#include <mrpt_vslam/core/ConfigFileWithDefaults.h>
#include <mrpt_vslam/core/ParticleFilterOptions.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace mrpt_vslam::core {

void loadParticleFilterOptions(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                               mrpt::bayes::CParticleFilter::TParticleFilterOptions& options)
{
    using PF = mrpt::bayes::CParticleFilter;
    using mrpt::typemeta::TEnumType;
    constexpr auto kProposal = PF::pfOptimalProposal;
    constexpr auto kResampling = PF::prSystematic;
    const ConfigFileWithDefaults withDefaults(
        cfg, section,
        {{"PF_algorithm", TEnumType<PF::TParticleFilterAlgorithm>::value2name(kProposal)},
         {"resamplingMethod", TEnumType<PF::TParticleResamplingAlgorithm>::value2name(kResampling)},
         {"BETA", "0.5"},
         {"adaptiveSampleSize", "false"}});
    const auto key = [&](const char* name) { return "[" + section + "] " + name; };

    // checked first: MRPT's loader asks an auxiliary filter for its own keys and asserts on a
    // negative range, in its own words
    readEnum(withDefaults, section, "PF_algorithm", kProposal,
             {PF::pfStandardProposal, PF::pfOptimalProposal});
    readEnum(withDefaults, section, "resamplingMethod", kResampling);
    const double range = withDefaults.read_double(section, "max_loglikelihood_dyn_range",
                                                  options.max_loglikelihood_dyn_range);
    if (!(range > 0 && std::isfinite(range)))
        throw std::invalid_argument(key("max_loglikelihood_dyn_range") + " must be finite and > 0");

    options.loadFromConfigFile(withDefaults, section);
    if (!(options.BETA >= 0 && options.BETA <= 1))
        throw std::invalid_argument(key("BETA") +
                                    " (the N_eff/N threshold of resampling) must be in [0, 1]");
    if (!(options.powFactor > 0 && options.powFactor <= 1))
        throw std::invalid_argument(key("powFactor") + " must be in (0, 1]");
}

}  // namespace mrpt_vslam::core
