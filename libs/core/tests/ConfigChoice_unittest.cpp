#include <gtest/gtest.h>
#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt_vslam/core/ConfigChoice.h>

#include <optional>
#include <stdexcept>
#include <string>

using mrpt_vslam::core::readChoice;
using mrpt_vslam::core::readEnum;
using PF = mrpt::bayes::CParticleFilter;

namespace {
/// `[s] k = <value>`, or a section without the key
mrpt::config::CConfigFileMemory config(const std::optional<std::string>& value)
{
    return mrpt::config::CConfigFileMemory(value ? "[s]\nk = " + *value + "\n" : "[s]\n");
}

PF::TParticleResamplingAlgorithm resampling(const std::optional<std::string>& value)
{
    return readEnum(config(value), "s", "k", PF::prSystematic);
}
}  // namespace

TEST(ConfigChoice, ReadsTheChoiceNamedAnAliasOrTheCurrentValueWhenAbsent)
{
    const std::vector<std::pair<std::string, int>> choices = {{"one", 1}, {"two", 2}, {"uno", 1}};
    EXPECT_EQ(readChoice(config("two"), "s", "k", choices, 1), 2);
    EXPECT_EQ(readChoice(config("uno"), "s", "k", choices, 2), 1);
    EXPECT_EQ(readChoice(config("eins"), "s", "k", choices, 2, {{"eins", 1}}), 1);
    EXPECT_EQ(readChoice(config(std::nullopt), "s", "k", choices, 2), 2);
    try {
        readChoice(config("three"), "s", "k", choices, 1, {{"eins", 1}});
        ADD_FAILURE() << "three accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()), "[s] k must be one, two or uno, not 'three'");
    }
}

TEST(ConfigChoice, ReadsAnEnumsNameOrTheNumberOfOne)
{
    EXPECT_EQ(resampling("prResidual"), PF::prResidual);
    EXPECT_EQ(resampling("prMultinomial"), PF::prMultinomial);
    EXPECT_EQ(resampling("2"), PF::prStratified);
    EXPECT_EQ(resampling("0"), PF::prMultinomial);
    EXPECT_EQ(resampling(std::nullopt), PF::prSystematic);
}

// read_enum() would pass 9 on as a value and name no choice for 'prFoo'
TEST(ConfigChoice, AnyOtherValueOfAnEnumIsAnErrorListingItsNames)
{
    for (const std::string value :
         {"9", "-1", "prFoo", "1x", "prresidual", "01", "", "prResidual x"}) {
        try {
            resampling(value);
            ADD_FAILURE() << value << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_EQ(std::string(e.what()),
                      "[s] k must be prMultinomial, prResidual, prStratified or prSystematic, "
                      "not '" +
                          value + "'");
        }
    }
}

TEST(ConfigChoice, AnEnumNarrowedToSomeValuesTakesOnlyTheirNamesAndNumbers)
{
    const auto read = [](const std::string& value) {
        return readEnum(config(value), "s", "k", PF::prSystematic,
                        {PF::prSystematic, PF::prResidual});
    };
    EXPECT_EQ(read("prResidual"), PF::prResidual);
    EXPECT_EQ(read("3"), PF::prSystematic);
    for (const std::string value : {"prMultinomial", "0", "2"}) {
        try {
            read(value);
            ADD_FAILURE() << value << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_EQ(std::string(e.what()),
                      "[s] k must be prResidual or prSystematic, not '" + value + "'");
        }
    }
}

TEST(ConfigChoice, ListsOneTwoOrMoreChoices)
{
    using mrpt_vslam::core::listOfChoices;
    EXPECT_EQ(listOfChoices({"a"}), "a");
    EXPECT_EQ(listOfChoices({"a", "b"}), "a or b");
    EXPECT_EQ(listOfChoices({"a", "b", "c"}), "a, b or c");
}
