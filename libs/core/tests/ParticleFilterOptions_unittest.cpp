#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt_vslam/core/ParticleFilterOptions.h>

#include <stdexcept>
#include <string>

using PF = mrpt::bayes::CParticleFilter;

namespace {
PF::TParticleFilterOptions load(const std::string& keys)
{
    PF::TParticleFilterOptions options;
    mrpt_vslam::core::loadParticleFilterOptions(
        mrpt::config::CConfigFileMemory("[ParticleFilter]\n" + keys), "ParticleFilter", options);
    return options;
}
}  // namespace

// MRPT requires these keys; absent, they take the recommended values, not MRPT's defaults
TEST(ParticleFilterOptions, KeysMrptRequiresTakeTheRecommendedValuesWhenAbsent)
{
    const auto options = load("sampleSize = 7\n");
    EXPECT_EQ(options.sampleSize, 7u);
    EXPECT_EQ(options.PF_algorithm, PF::pfOptimalProposal);
    EXPECT_EQ(options.resamplingMethod, PF::prSystematic);
    EXPECT_DOUBLE_EQ(options.BETA, 0.5);
    EXPECT_FALSE(options.adaptiveSampleSize);
    const PF::TParticleFilterOptions mrpts;
    EXPECT_NE(mrpts.PF_algorithm, options.PF_algorithm);
    EXPECT_NE(mrpts.resamplingMethod, options.resamplingMethod);

    const auto set = load(
        "sampleSize = 3\nPF_algorithm = 0\nresamplingMethod = prResidual\nBETA = 0.25\n"
        "adaptiveSampleSize = true\npowFactor = 0.5\n");
    EXPECT_EQ(set.PF_algorithm, PF::pfStandardProposal);
    EXPECT_EQ(set.resamplingMethod, PF::prResidual);
    EXPECT_DOUBLE_EQ(set.BETA, 0.25);
    EXPECT_TRUE(set.adaptiveSampleSize);
    EXPECT_DOUBLE_EQ(set.powFactor, 0.5);
}

TEST(ParticleFilterOptions, ImpossibleValuesAreRefusedNamingTheKey)
{
    const std::pair<std::string, std::string> refused[] = {
        {"PF_algorithm = pfAuxiliaryPFOptimal",
         "[ParticleFilter] PF_algorithm must be pfStandardProposal or pfOptimalProposal, not "
         "'pfAuxiliaryPFOptimal'"},
        {"PF_algorithm = 3",
         "[ParticleFilter] PF_algorithm must be pfStandardProposal or pfOptimalProposal, not '3'"},
        {"resamplingMethod = 9",
         "[ParticleFilter] resamplingMethod must be prMultinomial, prResidual, prStratified or "
         "prSystematic, not '9'"},
        {"BETA = 1.5",
         "[ParticleFilter] BETA (the N_eff/N threshold of resampling) must be in [0, 1]"},
        {"powFactor = 0", "[ParticleFilter] powFactor must be in (0, 1]"},
        {"max_loglikelihood_dyn_range = -1",
         "[ParticleFilter] max_loglikelihood_dyn_range must be finite and > 0"}};
    for (const auto& [key, message] : refused) {
        try {
            load("sampleSize = 3\n" + key + "\n");
            ADD_FAILURE() << key << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_EQ(std::string(e.what()), message);
        }
    }
    // the number of particles is the user's to set
    EXPECT_THROW(load("PF_algorithm = pfOptimalProposal\n"), std::exception);
}
