#include <gtest/gtest.h>
#include <mrpt_vslam/core/RunReport.h>
#include <mrpt_vslam/core/Version.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using mrpt_vslam::core::RunReport;
using mrpt_vslam::core::RunTimer;
using mrpt_vslam::core::TStepStatistics;
using nlohmann::json;

TEST(RunReport, AllFieldsAreWritten)
{
    RunReport r("omni-fastslam");
    r.setCommandLine({"omni-fastslam", "a.ini", "--seed", "3"});
    r.setConfig("a.ini", "[Filter]\nsampleSize = 100\n");
    r.setRawlog("data/x.rawlog");
    r.setSeed(3);
    r.setOpenCvVersion("4.6.0");
    r.setStartTime(std::chrono::system_clock::time_point(std::chrono::seconds(1700000000)));
    r.setCount("frames", 320);
    r.setCount("fraction", 0.25);
    RunTimer timer;
    for (double ms : {1.0, 2.0, 3.0, 4.0}) timer.addStep(ms);
    r.setTiming(12.5, timer.stepStatistics());
    r.setResult("landmarks", 41);
    r.setResultText("status", "ok");
    r.setResultJson("final_pose", R"({"x": 1.5, "y": -2})");
    r.addWarning("first");
    r.addWarning("second");

    const json j = json::parse(r.toJson());
    EXPECT_EQ(j["app"], "omni-fastslam");
    EXPECT_EQ(j["version"], mrpt_vslam::core::projectVersion());
    EXPECT_EQ(j["mrpt_version"], mrpt_vslam::core::mrptVersion());
    EXPECT_EQ(j["opencv_version"], "4.6.0");
    EXPECT_EQ(j["command_line"], json({"omni-fastslam", "a.ini", "--seed", "3"}));
    EXPECT_EQ(j["config_file"], "a.ini");
    EXPECT_EQ(j["config"], "[Filter]\nsampleSize = 100\n");
    EXPECT_EQ(j["rawlog"], "data/x.rawlog");
    EXPECT_EQ(j["seed"], 3);
    EXPECT_EQ(j["start_time"], "2023-11-14T22:13:20Z");
    EXPECT_TRUE(j["counts"]["frames"].is_number_integer());
    EXPECT_EQ(j["counts"]["frames"], 320);
    EXPECT_EQ(j["counts"]["fraction"], 0.25);
    EXPECT_EQ(j["timing"]["total_s"], 12.5);
    EXPECT_EQ(j["timing"]["steps"], 4);
    EXPECT_EQ(j["timing"]["per_step_ms"]["mean"], 2.5);
    EXPECT_EQ(j["timing"]["per_step_ms"]["median"], 2.5);
    EXPECT_EQ(j["timing"]["per_step_ms"]["p95"], 4);
    EXPECT_EQ(j["timing"]["per_step_ms"]["max"], 4);
    EXPECT_EQ(j["results"]["landmarks"], 41);
    EXPECT_EQ(j["results"]["status"], "ok");
    EXPECT_EQ(j["results"]["final_pose"]["x"], 1.5);
    EXPECT_EQ(j["warnings"], json({"first", "second"}));
    EXPECT_EQ(r.warnings(), (std::vector<std::string>{"first", "second"}));
    EXPECT_EQ(json::parse(RunReport("app").toJson())["warnings"], json::array());
}

TEST(RunReport, FieldOrderIsStable)
{
    const std::string text = RunReport("app").toJson();
    const char* const order[] = {
        "\"app\"",          "\"version\"",     "\"mrpt_version\"", "\"opencv_version\"",
        "\"command_line\"", "\"config_file\"", "\"config\"",       "\"rawlog\"",
        "\"seed\"",         "\"start_time\"",  "\"warnings\"",     "\"counts\"",
        "\"timing\"",       "\"results\""};
    size_t last = 0;
    for (const char* key : order) {
        const size_t at = text.find(key);
        ASSERT_NE(at, std::string::npos) << key;
        EXPECT_GT(at + 1, last) << key;
        last = at + 1;
    }
}

TEST(RunReport, NonFiniteNumbersBecomeNull)
{
    RunReport r("app");
    r.setCount("nan", std::nan(""));
    r.setResult("inf", std::numeric_limits<double>::infinity());
    TStepStatistics s;
    s.count = 1;
    s.mean_ms = s.median_ms = s.p95_ms = s.max_ms = -std::numeric_limits<double>::infinity();
    r.setTiming(std::nan(""), s);
    const std::string text = r.toJson();
    // The words only appear as the key names, never as values.
    EXPECT_EQ(text.find("nan", text.find("nan") + 1), std::string::npos);
    EXPECT_EQ(text.find("inf", text.find("inf") + 1), std::string::npos);
    const json j = json::parse(text);
    EXPECT_TRUE(j["counts"]["nan"].is_null());
    EXPECT_TRUE(j["results"]["inf"].is_null());
    EXPECT_TRUE(j["timing"]["total_s"].is_null());
    EXPECT_TRUE(j["timing"]["per_step_ms"]["p95"].is_null());
}

TEST(RunReport, UnsetFieldsAreNullAndNoStepsHaveNullStatistics)
{
    const json j = json::parse(RunReport("app").toJson());
    EXPECT_TRUE(j["opencv_version"].is_null());
    EXPECT_TRUE(j["rawlog"].is_null());
    EXPECT_TRUE(j["seed"].is_null());
    EXPECT_EQ(j["timing"]["steps"], 0);
    EXPECT_TRUE(j["timing"]["per_step_ms"]["mean"].is_null());
    EXPECT_TRUE(j["counts"].is_object());
    EXPECT_TRUE(j["counts"].empty());
    EXPECT_EQ(j["start_time"].get<std::string>().size(), 20u);
}

TEST(RunReport, InvalidResultJsonIsRejected)
{
    RunReport r("app");
    EXPECT_THROW(r.setResultJson("x", "{oops"), std::invalid_argument);
}

TEST(RunReport, WriteIsAtomicAndComplete)
{
    const std::string file =
        ::testing::TempDir() + "RunReport_run_" + std::to_string(::getpid()) + ".json";
    std::remove(file.c_str());
    RunReport r("app");
    r.setCount("frames", 7);
    r.write(file);
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), r.toJson());
    EXPECT_FALSE(std::ifstream(file + ".tmp").good());
    EXPECT_THROW(r.write("/nonexistent/dir/run.json"), std::runtime_error);
    std::remove(file.c_str());
}

TEST(RunReport, IsoTimeIsUtc)
{
    using std::chrono::seconds;
    using std::chrono::system_clock;
    EXPECT_EQ(RunReport::isoTimeUtc(system_clock::time_point(seconds(0))), "1970-01-01T00:00:00Z");
    EXPECT_EQ(RunReport::isoTimeUtc(system_clock::time_point(seconds(951782400))),
              "2000-02-29T00:00:00Z");
}

TEST(RunReport, SaysWhetherTheRunCompleted)
{
    mrpt_vslam::core::RunReport r("app");
    auto j = nlohmann::json::parse(r.toJson());
    EXPECT_EQ(j["completed"], false);
    EXPECT_TRUE(j["error"].is_null());
    r.setFailed("x.rawlog: step 3: timestamps go backwards");
    j = nlohmann::json::parse(r.toJson());
    EXPECT_EQ(j["completed"], false);
    EXPECT_EQ(j["error"], "x.rawlog: step 3: timestamps go backwards");
    mrpt_vslam::core::RunReport ok("app");
    ok.setCompleted();
    EXPECT_EQ(nlohmann::json::parse(ok.toJson())["completed"], true);
}
