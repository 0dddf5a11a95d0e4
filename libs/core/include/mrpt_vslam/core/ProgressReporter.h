#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <string>

namespace mrpt_vslam::core {

/** A progress line for long runs, rewritten in place with '\r':
 *  `[omni-fastslam] frame 120/320 (37%)  85.3 frames/s  ETA 2.3 s`
 *  When the total is unknown (0) it shows only the count and the rate. finish() writes the final
 *  line, ending `done in 3.8 s`, and a newline. A quiet reporter writes nothing.
 *
 *  Usage: `ProgressReporter progress(app, n_frames, args.quiet);` then `progress.update(i + 1)`
 *  after each frame (cheap: it redraws at most every `min_interval_s`), then `progress.finish()`.
 *  The stream and the clock can be injected (tests).
 */
class ProgressReporter {
  public:
    using Clock = std::chrono::steady_clock;
    using TimeSource = std::function<Clock::time_point()>;

    /** \param total number of units, 0 if unknown
     *  \param unit singular name of a unit ("frame"); the rate uses the plural (+"s")
     *  \param min_interval_s minimum time between redraws [s] */
    ProgressReporter(std::string app_name, size_t total, bool quiet, std::ostream& out,
                     TimeSource now = Clock::now, std::string unit = "frame",
                     double min_interval_s = 0.25);
    /** Writes to std::cerr: redrawn in place on a terminal, else a plain line every 5 s. */
    ProgressReporter(std::string app_name, size_t total, bool quiet);
    /** Ends a pending line with a newline, so later messages start on their own line. */
    ~ProgressReporter();
    ProgressReporter(const ProgressReporter&) = delete;
    ProgressReporter& operator=(const ProgressReporter&) = delete;

    /** Reports `done` units finished; redraws if at least min_interval_s passed since the last
     *  redraw (or nothing was drawn yet). */
    void update(size_t done);
    /** Draws the final line with `done` units and the total time, then a newline. Later
     *  update() and finish() calls are ignored. */
    void finish(size_t done);

    /** The line text for `done` units after `elapsed_s` seconds (no '\r'). */
    std::string formatLine(size_t done, double elapsed_s, bool final_line) const;

  private:
    void draw(const std::string& line);

    std::string m_app;
    size_t m_total;
    bool m_quiet;
    std::ostream& m_out;
    TimeSource m_now;
    std::string m_unit;
    double m_min_interval_s;
    Clock::time_point m_start;
    Clock::time_point m_last_draw;
    bool m_in_place = true;  ///< redraw one line with '\r' (a terminal) or print lines (a log)
    bool m_drawn = false;
    bool m_finished = false;
    size_t m_last_width = 0;
};

}  // namespace mrpt_vslam::core
