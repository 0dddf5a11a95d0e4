#include <mrpt_vslam/core/ConfigChoice.h>
#include <mrpt_vslam/core/ConfigFileWithDefaults.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/core/ParticleFilterOptions.h>

#include <cmath>
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
    // the key with its section in front, as requireOption() leaves it to the reader
    const auto key = [&](const char* name) { return "[" + section + "] " + name; };

    // checked first: MRPT's loader asks an auxiliary filter for its own keys and asserts on a
    // negative range, in its own words
    readEnum(withDefaults, section, "PF_algorithm", kProposal,
             {PF::pfStandardProposal, PF::pfOptimalProposal});
    readEnum(withDefaults, section, "resamplingMethod", kResampling);
    const double range = withDefaults.read_double(section, "max_loglikelihood_dyn_range",
                                                  options.max_loglikelihood_dyn_range);
    requireOption(range > 0 && std::isfinite(range), key("max_loglikelihood_dyn_range"),
                  "must be finite and > 0");

    options.loadFromConfigFile(withDefaults, section);
    requireOption(options.BETA >= 0 && options.BETA <= 1, key("BETA"),
                  "(the N_eff/N threshold of resampling) must be in [0, 1]");
    requireOption(options.powFactor > 0 && options.powFactor <= 1, key("powFactor"),
                  "must be in (0, 1]");
}

}  // namespace mrpt_vslam::core
