#include <mrpt_vslam/team/ReadingMerger.h>

#include <algorithm>
#include <stdexcept>

namespace mrpt_vslam::team {

ReadingMerger::ReadingMerger(std::vector<std::string> robots, double reorder_window_s,
                             double join_window_s)
    : m_robots(std::move(robots)),
      m_window(reorder_window_s),
      m_join_window(join_window_s),
      m_state(m_robots.size())
{
    if (!(m_window > 0 && m_join_window > 0))
        throw std::invalid_argument("reorder and join windows must be > 0");
}

std::optional<size_t> ReadingMerger::robotIndex(const std::string& robot) const
{
    const auto it = std::find(m_robots.begin(), m_robots.end(), robot);
    if (it == m_robots.end()) return std::nullopt;
    return static_cast<size_t>(it - m_robots.begin());
}

void ReadingMerger::add(size_t robot, mrpt::obs::CObservation::Ptr observation,
                        mrpt::Clock::time_point watermark, double sent_time, double now)
{
    auto& s = m_state.at(robot);
    s.queue.push_back({std::move(observation), sent_time, now});
    s.watermark = std::max(s.watermark, watermark);
    // caught up with the stream: it holds the others back again
    if (s.silent && m_stream_time != INVALID_TIMESTAMP && s.watermark > m_stream_time)
        s.silent = false;
}

void ReadingMerger::finish(size_t robot) { m_state.at(robot).finished = true; }

std::optional<size_t> ReadingMerger::oldest() const
{
    std::optional<size_t> best;
    for (size_t r = 0; r < m_state.size(); r++) {
        if (m_state[r].queue.empty()) continue;
        const auto t = m_state[r].queue.front().observation->timestamp;
        if (!best || t < m_state[*best].queue.front().observation->timestamp) best = r;
    }
    return best;
}

bool ReadingMerger::holdsBack(size_t robot, mrpt::Clock::time_point t, size_t of) const
{
    const auto& s = m_state[robot];
    if (robot == of || s.finished || s.silent) return false;
    // readings at t of a robot listed before `of` go first
    return s.watermark < t || (s.watermark == t && robot < of);
}

std::optional<double> ReadingMerger::releaseTime(size_t robot) const
{
    const auto t = m_state[robot].queue.front().observation->timestamp;
    std::optional<double> window;
    for (size_t k = 0; k < m_state.size(); k++) {
        if (!holdsBack(k, t, robot)) continue;
        const bool newcomer = m_state[k].watermark == mrpt::Clock::time_point::min();
        window = std::max(window.value_or(0), newcomer ? m_join_window : m_window);
    }
    if (!window) return std::nullopt;
    return m_state[robot].queue.front().arrival + *window;
}

std::optional<double> ReadingMerger::deadline() const
{
    const auto r = oldest();
    if (!r) return std::nullopt;
    return releaseTime(*r).value_or(m_state[*r].queue.front().arrival);
}

std::optional<ReadingMerger::TReleased> ReadingMerger::next(double now)
{
    const auto r = oldest();
    if (!r) return std::nullopt;
    auto& s = m_state[*r];
    const auto t = s.queue.front().observation->timestamp;
    if (const auto at = releaseTime(*r)) {
        if (now < *at) return std::nullopt;
        m_window_expiries++;
        for (size_t k = 0; k < m_state.size(); k++)
            if (holdsBack(k, t, *r)) m_state[k].silent = true;
    }
    TReleased out;
    out.robot = *r;
    out.observation = std::move(s.queue.front().observation);
    out.sent_time = s.queue.front().sent_time;
    out.original_time = t;
    s.queue.pop_front();
    if (m_stream_time != INVALID_TIMESTAMP && t < m_stream_time) {
        // late: just after the stream's time, one stamp per timestamp of the robot
        out.late = true;
        const bool sameGroup = s.late_original == t && s.late_stamp >= m_stream_time;
        const auto stamp = sameGroup ? s.late_stamp : m_stream_time + kLateStep;
        s.late_original = t;
        s.late_stamp = stamp;
        out.observation->timestamp = stamp;
    }
    m_stream_time = out.observation->timestamp;
    return out;
}

bool ReadingMerger::settled(mrpt::Clock::time_point t) const
{
    for (size_t r = 0; r < m_state.size(); r++) {
        const auto& s = m_state[r];
        if (!s.queue.empty() && s.queue.front().observation->timestamp <= t) return false;
        if (!s.finished && !s.silent && s.watermark <= t) return false;
    }
    return true;
}

bool ReadingMerger::done() const
{
    return std::all_of(m_state.begin(), m_state.end(),
                       [](const TRobotState& s) { return s.finished && s.queue.empty(); });
}

}  // namespace mrpt_vslam::team
