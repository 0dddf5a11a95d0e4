#include <mrpt_vslam/core/RunTimer.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace mrpt_vslam::core {

RunTimer::RunTimer() : m_run_start(Clock::now()) {}

void RunTimer::startStep()
{
    m_step_start = Clock::now();
    m_step_running = true;
}

double RunTimer::endStep()
{
    if (!m_step_running) throw std::logic_error("RunTimer::endStep() without startStep()");
    const double ms =
        std::chrono::duration<double, std::milli>(Clock::now() - m_step_start).count();
    m_step_running = false;
    m_steps_ms.push_back(ms);
    return ms;
}

void RunTimer::addStep(double duration_ms)
{
    if (!(duration_ms >= 0))
        throw std::invalid_argument("RunTimer::addStep(): invalid duration " +
                                    std::to_string(duration_ms) + " ms");
    m_steps_ms.push_back(duration_ms);
}

double RunTimer::elapsedSeconds() const
{
    return std::chrono::duration<double>(Clock::now() - m_run_start).count();
}

TStepStatistics RunTimer::stepStatistics() const
{
    TStepStatistics s;
    s.count = m_steps_ms.size();
    if (s.count == 0) return s;
    std::vector<double> sorted = m_steps_ms;
    std::sort(sorted.begin(), sorted.end());
    const size_t n = sorted.size();
    s.total_ms = std::accumulate(sorted.begin(), sorted.end(), 0.0);
    s.mean_ms = s.total_ms / static_cast<double>(n);
    s.median_ms = n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    const auto rank = static_cast<size_t>(std::ceil(0.95 * static_cast<double>(n)));
    s.p95_ms = sorted[std::max<size_t>(rank, 1) - 1];
    s.max_ms = sorted.back();
    return s;
}

}  // namespace mrpt_vslam::core
