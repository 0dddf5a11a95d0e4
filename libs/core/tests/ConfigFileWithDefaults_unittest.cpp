#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/ConfigFileWithDefaults.h>

#include <stdexcept>
#include <string>

using mrpt_vslam::core::ConfigFileWithDefaults;

TEST(ConfigFileWithDefaults, AnAbsentKeyOfTheSectionReadsAsItsDefault)
{
    const mrpt::config::CConfigFileMemory config("[S]\nset = 3\n[T]\nother = 1\n");
    const ConfigFileWithDefaults cfg(config, "S", {{"set", "7"}, {"absent", "2.5"}});
    EXPECT_EQ(cfg.read_int("S", "set", 0, true), 3);
    EXPECT_DOUBLE_EQ(cfg.read_double("S", "absent", 0, true), 2.5);
    EXPECT_EQ(cfg.read_int("T", "other", 0, true), 1);
    EXPECT_EQ(cfg.read_int("S", "unlisted", 4), 4);
    // a key with no default is as required as in the configuration read through
    EXPECT_THROW(cfg.read_int("S", "unlisted", 0, true), std::exception);
    EXPECT_THROW(cfg.read_int("T", "absent", 0, true), std::exception);
    EXPECT_TRUE(cfg.keyExists("T", "other"));
}

// The configuration read through records the default as the value read: options.ini lists it.
TEST(ConfigFileWithDefaults, TheConfigurationReadThroughRecordsTheDefault)
{
    mrpt_vslam::core::CheckedConfigFile config;
    config.loadText("[S]\nset = 3\n", "t.ini");
    const ConfigFileWithDefaults cfg(config, "S", {{"absent", "2.5"}});
    cfg.read_int("S", "set", 0, true);
    cfg.read_double("S", "absent", 0, true);
    EXPECT_EQ(config.optionsInUseText(),
              "# Every key read from t.ini, with the value it was read with\n\n[S]\nset = 3\n"
              "# not set: the program's defaults\nabsent = 2.5\n");
}
