#include <mrpt_vslam/core/AtomicFile.h>
#include <mrpt_vslam/core/RunReport.h>
#include <mrpt_vslam/core/Version.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace mrpt_vslam::core {
namespace {

using Json = nlohmann::ordered_json;

/** null for NaN/inf; an integer for integral values that a double holds exactly. */
Json number(double v)
{
    if (!std::isfinite(v)) return nullptr;
    if (std::trunc(v) == v && std::abs(v) < 9007199254740992.0)  // 2^53
        return static_cast<int64_t>(v);
    return v;
}

}  // namespace

struct RunReport::Impl {
    Json doc;
};

RunReport::RunReport(const std::string& app_name) : m_impl(std::make_unique<Impl>())
{
    Json& d = m_impl->doc;
    d["app"] = app_name;
    d["version"] = projectVersion();
    d["mrpt_version"] = mrptVersion();
    for (const char* key : {"opencv_version", "command_line", "config_file", "config", "rawlog",
                            "ground_truth", "seed", "start_time"})
        d[key] = nullptr;
    d["completed"] = false;
    d["error"] = nullptr;
    d["warnings"] = Json::array();
    d["counts"] = Json::object();
    d["timing"] = {{"threads", 1},
                   {"total_s", nullptr},
                   {"steps", 0},
                   {"per_step_ms",
                    {{"mean", nullptr}, {"median", nullptr}, {"p95", nullptr}, {"max", nullptr}}}};
    d["results"] = Json::object();
    setStartTime(std::chrono::system_clock::now());
}

RunReport::~RunReport() = default;

void RunReport::setCommandLine(const std::vector<std::string>& args)
{
    m_impl->doc["command_line"] = args;
}

void RunReport::setConfig(const std::string& file, const std::string& effective_text)
{
    m_impl->doc["config_file"] = file;
    m_impl->doc["config"] = effective_text;
}

void RunReport::setRawlog(const std::string& file) { m_impl->doc["rawlog"] = file; }
void RunReport::setGroundTruth(const std::string& name) { m_impl->doc["ground_truth"] = name; }
void RunReport::setSeed(uint32_t seed) { m_impl->doc["seed"] = seed; }
void RunReport::setThreads(unsigned threads) { m_impl->doc["timing"]["threads"] = threads; }
void RunReport::setOpenCvVersion(const std::string& v) { m_impl->doc["opencv_version"] = v; }

void RunReport::setStartTime(std::chrono::system_clock::time_point t)
{
    m_impl->doc["start_time"] = isoTimeUtc(t);
}

void RunReport::setCompleted() { m_impl->doc["completed"] = true; }

void RunReport::setFailed(const std::string& error)
{
    m_impl->doc["completed"] = false;
    m_impl->doc["error"] = error;
}

void RunReport::addWarning(const std::string& text) { m_impl->doc["warnings"].push_back(text); }

std::vector<std::string> RunReport::warnings() const
{
    return m_impl->doc.at("warnings").get<std::vector<std::string>>();
}

void RunReport::setCount(const std::string& name, double value)
{
    m_impl->doc["counts"][name] = number(value);
}

void RunReport::setTiming(double total_s, const TStepStatistics& steps)
{
    Json& t = m_impl->doc["timing"];
    t["total_s"] = number(total_s);
    t["steps"] = steps.count;
    const bool any = steps.count > 0;
    t["per_step_ms"] = {{"mean", any ? number(steps.mean_ms) : Json()},
                        {"median", any ? number(steps.median_ms) : Json()},
                        {"p95", any ? number(steps.p95_ms) : Json()},
                        {"max", any ? number(steps.max_ms) : Json()}};
}

void RunReport::setTiming(const RunTimer& timer)
{
    setTiming(timer.elapsedSeconds(), timer.stepStatistics());
}

void RunReport::setPartTiming(const std::string& name, double seconds)
{
    m_impl->doc["timing"][name + "_s"] = number(seconds);
}

void RunReport::setResult(const std::string& name, double value)
{
    m_impl->doc["results"][name] = number(value);
}

void RunReport::setResultText(const std::string& name, const std::string& text)
{
    m_impl->doc["results"][name] = text;
}

void RunReport::setResultJson(const std::string& name, const std::string& json_text)
{
    try {
        m_impl->doc["results"][name] = Json::parse(json_text);
    } catch (const Json::parse_error& e) {
        throw std::invalid_argument("run.json result '" + name +
                                    "' is not valid JSON: " + e.what());
    }
}

std::string RunReport::toJson() const
{
    // Non-finite numbers never reach the document (number() makes them null).
    return m_impl->doc.dump(2) + "\n";
}

void RunReport::write(const std::string& file) const
{
    AtomicFile out(file);
    out.stream() << toJson();
    out.commit();
}

std::string RunReport::isoTimeUtc(std::chrono::system_clock::time_point t)
{
    const std::time_t secs = std::chrono::system_clock::to_time_t(t);
    std::tm utc{};
    gmtime_r(&secs, &utc);
    char buf[32];
    std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &utc);
    return buf;
}

std::string jsonNumber(double v, int decimals)
{
    if (!std::isfinite(v)) return "null";
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, v);
    return text;
}

}  // namespace mrpt_vslam::core
