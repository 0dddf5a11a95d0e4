#pragma once

#include <mrpt_vslam/core/RunTimer.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** The `run.json` of a run folder: what was run, with what, and how long it took.
 *
 *  Fields, in this order (doc/app-conventions.md): app, version, mrpt_version, opencv_version,
 *  command_line, config_file, config (effective text), rawlog, ground_truth, seed, start_time (ISO
 * 8601 UTC), completed (false until setCompleted()), error (setFailed()), warnings [text],
 * counts {name: number},
 * timing {total_s, steps, per_step_ms {mean, median, p95, max}}, results {name: value}. Fields
 * never set are null; non-finite numbers are written as null.
 *
 *  Usage: create at start-up (records the start time), fill it as the run goes, write() at
 *  the end (atomically, so a run.json is always complete).
 */
class RunReport {
  public:
    explicit RunReport(const std::string& app_name);
    ~RunReport();
    RunReport(const RunReport&) = delete;
    RunReport& operator=(const RunReport&) = delete;

    /** @name What was run
     *  @{ */
    void setCommandLine(const std::vector<std::string>& args);
    void setConfig(const std::string& file, const std::string& effective_text);
    void setRawlog(const std::string& file);
    /** Ground truth the run was compared with (`NAME` prefix or file); vslam-eval reads it. */
    void setGroundTruth(const std::string& name);
    void setSeed(uint32_t seed);
    /// Threads the run used (timing.threads; the results do not depend on it).
    void setThreads(unsigned threads);
    void setOpenCvVersion(const std::string& version);
    void setStartTime(std::chrono::system_clock::time_point t);
    /** The run went to its end: every output of the folder is written. */
    void setCompleted();
    /** The run stopped with `error`: the folder's other outputs are missing or partial. */
    void setFailed(const std::string& error);
    /** @} */

    /** @name What came out
     *  @{ */
    /** Something the user should know of a run that completed (one line, without the app's
     *  name), e.g. that its observations barely corrected the odometry. */
    void addWarning(const std::string& text);
    std::vector<std::string> warnings() const;
    /** A count (frames, observations, landmarks...); integral values are written as integers. */
    void setCount(const std::string& name, double value);
    void setTiming(double total_s, const TStepStatistics& steps);
    void setTiming(const RunTimer& timer);
    /** The time of one part of the run beside the steps (`timing.<name>_s`), e.g. a smoothing
     *  after the last step: timings stay out of the results, which a seed reproduces. */
    void setPartTiming(const std::string& name, double seconds);
    void setResult(const std::string& name, double value);
    void setResultText(const std::string& name, const std::string& text);
    /** A result given as JSON text (object, array...). Throws std::invalid_argument if it does
     *  not parse. */
    void setResultJson(const std::string& name, const std::string& json_text);
    /** @} */

    /** The report as indented JSON text. */
    std::string toJson() const;
    /** Writes toJson() atomically to `file`. */
    void write(const std::string& file) const;

    /** "YYYY-MM-DDTHH:MM:SSZ". */
    static std::string isoTimeUtc(std::chrono::system_clock::time_point t);

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

/** `v` with `decimals` decimals as a number of setResultJson() text, or null where it is not
 *  finite, as the report writes its own numbers. */
std::string jsonNumber(double v, int decimals);

}  // namespace mrpt_vslam::core
