#pragma once

#include <chrono>
#include <cstddef>
#include <vector>

namespace mrpt_vslam::core {

/** Summary of the step durations of a run, in milliseconds. All zero when there are no steps. */
struct TStepStatistics {
    size_t count = 0;
    double total_ms = 0;
    double mean_ms = 0;
    double median_ms = 0;  ///< middle value; mean of the two middle ones for an even count
    double p95_ms = 0;     ///< nearest rank: the ceil(0.95 n)-th smallest
    double max_ms = 0;
};

/** Wall-clock timing of a run and of each of its steps (one filter update, one frame).
 *
 *  Usage: construct at the start of the run; around each step call startStep() / endStep();
 *  at the end read elapsedSeconds() and stepStatistics() (RunReport::setTiming() takes it whole).
 */
class RunTimer {
  public:
    using Clock = std::chrono::steady_clock;

    RunTimer();

    /** Starts timing a step. */
    void startStep();
    /** Ends the step started by startStep() and records it. \return its duration [ms].
     *  Throws std::logic_error if no step is running. */
    double endStep();
    /** Records a step measured elsewhere. \param duration_ms [ms], >= 0 */
    void addStep(double duration_ms);

    /** Time since construction [s]. */
    double elapsedSeconds() const;
    const std::vector<double>& stepDurationsMs() const { return m_steps_ms; }
    TStepStatistics stepStatistics() const;

  private:
    Clock::time_point m_run_start;
    Clock::time_point m_step_start;
    bool m_step_running = false;
    std::vector<double> m_steps_ms;
};

}  // namespace mrpt_vslam::core
