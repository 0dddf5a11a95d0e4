#pragma once

#include <mrpt/core/Clock.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/system/datetime.h>

#include <chrono>
#include <cstddef>
#include <deque>
#include <optional>
#include <string>
#include <vector>

namespace mrpt_vslam::team {

/** Merges the robots' reading streams into one in timestamp order, as one rawlog of the whole
 *  team would hold them (doc/team-online.md). Each robot's readings arrive in its own time order,
 *  each with a watermark (no later reading of the robot is older than it).
 *
 *  The oldest reading waiting (ties: the robot listed first) goes out once every other robot's
 *  watermark has passed it, or has finished; so when no reading is lost or late the merged
 *  stream is the one the team's rawlog gives. A robot that holds the oldest reading back for
 *  longer than `reorder_window_s` (wall clock; `join_window_s` while it has sent nothing yet) is
 *  taken as silent: the others go on without it until its watermark passes the stream's time
 *  again. Its readings older than the stream's time
 *  (those of a silent or late-joining robot) go out at once, late, stamped kLateStep after the
 *  stream's time (readings of one timestamp keep one stamp), so that the merged stream never goes
 * back in time: their odometry increments and measurements are whole, only their time is the
 * stream's.
 */
class ReadingMerger {
  public:
    /// A reading that goes out.
    struct TReleased {
        size_t robot = 0;
        mrpt::obs::CObservation::Ptr observation;  ///< timestamp: its place in the stream
        mrpt::Clock::time_point original_time;     ///< the reading's own timestamp
        double sent_time = 0;                      ///< node's wall clock when sent [s]
        bool late = false;                         ///< stamped anew (see above)
    };

    /// How far apart late readings of different timestamps are stamped (apart in a TUM file).
    static constexpr mrpt::Clock::duration kLateStep = std::chrono::microseconds(10);

    /// \param robots the team, in the order that breaks timestamp ties
    ReadingMerger(std::vector<std::string> robots, double reorder_window_s, double join_window_s);

    /// The robot's index, or nullopt if it is not in the team.
    std::optional<size_t> robotIndex(const std::string& robot) const;
    const std::vector<std::string>& robots() const { return m_robots; }

    /** The next reading of `robot` (arrival `now`, wall clock [s]); `watermark`: nothing older
     *  than it follows from this robot. */
    void add(size_t robot, mrpt::obs::CObservation::Ptr observation,
             mrpt::Clock::time_point watermark, double sent_time, double now);
    /// `robot` has sent its last reading.
    void finish(size_t robot);

    /// The next reading of the merged stream that can go out at wall time `now`, if any.
    std::optional<TReleased> next(double now);
    /** The wall time at which next() will release the oldest waiting reading even if robots
     *  still hold it back; nullopt when nothing waits. */
    std::optional<double> deadline() const;

    /// Every robot finished and every reading went out.
    bool done() const;
    /** No reading at or before `t` can still go out on time: every robot's watermark has passed
     *  it, or the robot finished or is silent (its readings would be late, stamped after it). */
    bool settled(mrpt::Clock::time_point t) const;
    bool finished(size_t robot) const { return m_state[robot].finished; }
    /// The time the merged stream has reached (INVALID_TIMESTAMP before the first reading).
    mrpt::Clock::time_point streamTime() const { return m_stream_time; }
    /// How many times the window ran out waiting for a robot.
    size_t windowExpiries() const { return m_window_expiries; }

  private:
    struct TQueued {
        mrpt::obs::CObservation::Ptr observation;
        double sent_time = 0;
        double arrival = 0;
    };
    struct TRobotState {
        std::deque<TQueued> queue;
        mrpt::Clock::time_point watermark = mrpt::Clock::time_point::min();
        bool finished = false;
        bool silent = false;
        /// The last late timestamp of the robot and the stamp it got.
        mrpt::Clock::time_point late_original = INVALID_TIMESTAMP, late_stamp = INVALID_TIMESTAMP;
    };
    /// The robot whose front reading is the oldest waiting (ties: lowest index).
    std::optional<size_t> oldest() const;
    /** When the front reading of `robot` goes out though robots hold it back (its arrival plus
     *  the longest window of those); nullopt if none does. */
    std::optional<double> releaseTime(size_t robot) const;
    /// Whether `robot` can still send a reading that goes before (time t, robot `of`).
    bool holdsBack(size_t robot, mrpt::Clock::time_point t, size_t of) const;

    std::vector<std::string> m_robots;
    double m_window = 1, m_join_window = 10;
    std::vector<TRobotState> m_state;
    mrpt::Clock::time_point m_stream_time = INVALID_TIMESTAMP;
    size_t m_window_expiries = 0;
};

}  // namespace mrpt_vslam::team
