#include <gtest/gtest.h>
#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt_vslam/core/ConfigEnum.h>

#include <optional>
#include <stdexcept>
#include <string>

using mrpt_vslam::core::readEnum;
using PF = mrpt::bayes::CParticleFilter;

namespace {
/// readEnum() of `[pf] resamplingMethod = <value>`, or of an absent key
PF::TParticleResamplingAlgorithm resampling(const std::optional<std::string>& value)
{
    mrpt::config::CConfigFileMemory cfg(value ? "[pf]\nresamplingMethod = " + *value + "\n"
                                              : "[pf]\n");
    return readEnum(cfg, "pf", "resamplingMethod", PF::prSystematic);
}
}  // namespace

TEST(ConfigEnum, ReadsANameOrTheNumberOfOneAndTheDefaultWhenAbsent)
{
    EXPECT_EQ(resampling("prResidual"), PF::prResidual);
    EXPECT_EQ(resampling("prMultinomial"), PF::prMultinomial);
    EXPECT_EQ(resampling("2"), PF::prStratified);
    EXPECT_EQ(resampling("0"), PF::prMultinomial);
    EXPECT_EQ(resampling(std::nullopt), PF::prSystematic);
}

// read_enum() would pass 9 on as a value and name no choice for 'prFoo'
TEST(ConfigEnum, AnyOtherValueIsAnErrorListingTheChoices)
{
    for (const std::string value : {"9", "-1", "prFoo", "1x", "prresidual", "01", ""}) {
        try {
            resampling(value);
            ADD_FAILURE() << value << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_EQ(std::string(e.what()),
                      "[pf] resamplingMethod must be prMultinomial, prResidual, prStratified or "
                      "prSystematic, not '" +
                          value + "'");
        }
    }
}

TEST(ConfigEnum, ListsOneTwoOrMoreChoices)
{
    using mrpt_vslam::core::listOfChoices;
    EXPECT_EQ(listOfChoices({"a"}), "a");
    EXPECT_EQ(listOfChoices({"a", "b"}), "a or b");
    EXPECT_EQ(listOfChoices({"a", "b", "c"}), "a, b or c");
}
