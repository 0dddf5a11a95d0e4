// Every configuration key of each driver app, set to values no key of its kind can take: the app
// refuses each with one line naming the key, before it reads any data. The keys are those the
// app itself reads (configKeys()) with each of its shipped configurations, defaults included.
#include <gtest/gtest.h>
#include <mrpt_vslam/apps/MultiRobotVSLAMApp.h>
#include <mrpt_vslam/apps/OmniFastSLAMApp.h>
#include <mrpt_vslam/apps/ViewSLAMApp.h>
#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/UsageError.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <string>
#include <utility>
#include <vector>

using namespace mrpt_vslam;

namespace {
const std::string kSource = MRPT_VSLAM_SOURCE_DIR;
const std::string kConfigs = kSource + "/share/mrpt-vslam/config/";
const std::string kData = kSource + "/datasets/";

/// A shipped configuration and a shipped rawlog it runs on.
using TConfigAndRawlog = std::pair<std::string, std::string>;

/// Values that no key of the kind can take.
const std::map<core::TReadKey::Kind, std::vector<std::string>> kImpossible{
    {core::TReadKey::Kind::Real, {"nan", "-inf", "1e400", "abc", ""}},
    {core::TReadKey::Kind::Integer, {"1.5", "1e12", "abc", ""}},
    {core::TReadKey::Kind::IntegerOrBoolean, {"maybe", "0.5"}},
};

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

core::AppArguments args(const std::string& app, const std::vector<std::string>& extra)
{
    std::vector<const char*> argv{app.c_str()};
    for (const auto& a : extra) argv.push_back(a.c_str());
    return core::AppArguments::parse(static_cast<int>(argv.size()), argv.data(), app, "");
}

/** For each app: every key of `runs`' configurations is set in turn to each impossible value of
 *  its kind (with the first configuration that reads it); initialize() must throw a one-line
 *  UsageError naming "[section] key". */
template <class APP>
void checkEveryKey(const std::string& app, const std::vector<TConfigAndRawlog>& runs)
{
    std::map<std::pair<std::string, std::string>, std::pair<core::TReadKey, TConfigAndRawlog>> keys;
    for (const auto& run : runs) {
        APP shipped(args(app, {run.first, run.second, "--quiet"}));
        ASSERT_NO_THROW(shipped.initialize()) << run.first;
        for (const auto& k : shipped.configKeys())
            keys.emplace(std::make_pair(lower(k.section), lower(k.key)), std::make_pair(k, run));
    }
    size_t checked = 0;
    for (const auto& [id, entry] : keys) {
        const auto& [key, run] = entry;
        const auto values = kImpossible.find(key.kind);
        if (values == kImpossible.end()) continue;  // text: each app checks its own
        for (const std::string& value : values->second) {
            const std::string setting = key.section + "." + key.key + "=" + value;
            APP bad(args(app, {run.first, run.second, "--set", setting, "--quiet"}));
            try {
                bad.initialize();
                ADD_FAILURE() << app << " " << run.first << ": " << setting << " accepted";
            } catch (const core::UsageError& e) {
                const std::string what = e.what();
                EXPECT_NE(lower(what).find("[" + id.first + "] " + id.second), std::string::npos)
                    << setting << ": " << what;
                EXPECT_EQ(what.find('\n'), std::string::npos) << setting << ": " << what;
            } catch (const std::exception& e) {
                ADD_FAILURE() << setting << ": not a usage error: " << e.what();
            }
            checked++;
        }
    }
    // the sweep covers the apps' options, not a few of them
    EXPECT_GE(keys.size(), 30u) << app;
    ::testing::Test::RecordProperty("values_checked", static_cast<int>(checked));
}
}  // namespace

TEST(EveryConfigKey, OmniFastSLAMRefusesImpossibleValuesOfEveryKey)
{
    checkEveryKey<apps::OmniFastSLAMApp>(
        "omni-fastslam",
        {{kConfigs + "omni-fastslam/sports-hall.ini", kData + "sports-hall/hall.rawlog"},
         {kConfigs + "omni-fastslam/template.ini", kData + "sports-hall/hall.rawlog"},
         {kConfigs + "omni-fastslam/mrclam-bearing-only.ini",
          kData + "utias-mrclam/mrclam7-r123-0-300.rawlog"}});
}

TEST(EveryConfigKey, MultiRobotVSLAMRefusesImpossibleValuesOfEveryKey)
{
    checkEveryKey<apps::MultiRobotVSLAMApp>(
        "multirobot-vslam",
        {{kConfigs + "multirobot-vslam/office-team-2.ini", kData + "office-team/team2.rawlog"},
         {kConfigs + "multirobot-vslam/office-team-3.ini", kData + "office-team/team3.rawlog"},
         {kConfigs + "multirobot-vslam/office-team-2.ini",
          kData + "office-team/team2-stereo-short.rawlog"},
         {kConfigs + "multirobot-vslam/mrclam.ini",
          kData + "utias-mrclam/mrclam7-r123-0-300.rawlog"}});
}

TEST(EveryConfigKey, ViewSLAMRefusesImpossibleValuesOfEveryKey)
{
    checkEveryKey<apps::ViewSLAMApp>(
        "view-slam", {{kConfigs + "view-slam/omni-views.ini", kData + "omni-views/rooms.rawlog"},
                      {kConfigs + "view-slam/template.ini", kData + "omni-views/rooms.rawlog"}});
}

// A second kind of map in [MappingApplication], with an option its loader refuses: one line,
// before MRPT's map registry loads it (MRPT 2.5 leaks a definition whose loader throws; the
// sanitizer build checks that nothing leaks).
TEST(EveryConfigKey, AnotherKindOfMapIsRefusedInOneLine)
{
    const auto expectRefused = [](auto&& app, const std::string& name) {
        try {
            app.initialize();
            ADD_FAILURE() << name << ": accepted";
        } catch (const core::UsageError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("must define exactly one map"), std::string::npos) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    };
    expectRefused(
        apps::OmniFastSLAMApp(
            args("omni-fastslam",
                 {kConfigs + "omni-fastslam/sports-hall.ini", kData + "sports-hall/hall.rawlog",
                  "--set", "MappingApplication.visualLandmarksMap_count=1", "--set",
                  "MappingApplication_visualLandmarksMap_00_insertOpts.D0=-1", "--quiet"})),
        "omni-fastslam");
    expectRefused(
        apps::MultiRobotVSLAMApp(args(
            "multirobot-vslam",
            {kConfigs + "multirobot-vslam/office-team-2.ini", kData + "office-team/team2.rawlog",
             "--set", "MappingApplication.ceilingLightsMap_count=1", "--set",
             "MappingApplication_ceilingLightsMap_00_insertOpts.p_new_mahalanobis2=-1",
             "--quiet"})),
        "multirobot-vslam");
}
