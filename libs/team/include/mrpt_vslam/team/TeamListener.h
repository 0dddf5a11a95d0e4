#pragma once

#include <mrpt_vslam/core/RawlogEntrySource.h>

#include <memory>
#include <string>
#include <vector>

namespace mrpt_vslam::team {

/** The mapper's end of the team link (doc/team-online.md): binds a ZeroMQ ROUTER socket at an
 *  address, takes the readings that robot nodes (RobotNode) send, acknowledges them, and hands
 *  them to the filter's steps in the order of a ReadingMerger, as a rawlog reader would.
 *  A robot's readings are taken in sequence only (a gap is sent again by its node, a repeat is
 *  dropped), so none is lost or taken twice across a node's restarts.
 *  The data end when every robot has sent its last reading, or when no message has come for
 *  `idle_timeout_s` (the robots not finished then are named in statsJson()). Once the robots'
 *  watermarks show that no more readings of the stream's time can come on time, it hands out a
 *  time barrier (core::TRawlogEntry::time_barrier), so that the step of that time is made at once
 *  rather than when a later reading arrives. A thread of its own
 *  takes and acknowledges the messages while the filter runs, until the data end.
 *  Usage: `TeamListener in("tcp://0.0.0.0:5555", {"R1", "R2"}, {});` then
 *  `ActionFrameSource steps(in, ...);`
 */
class TeamListener : public core::RawlogEntrySource {
  public:
    struct TOptions {
        double reorder_window_s = 1.0;  ///< ReadingMerger's window [s]
        double join_window_s = 10;      ///< ReadingMerger's window for robots not heard yet [s]
        double idle_timeout_s = 60;     ///< end when no message came for this long [s]
        bool quiet = false;             ///< no line per node that connects
    };
    /// Per robot, what came and how long it took.
    struct TRobotStats {
        size_t readings = 0;     ///< taken (each once)
        size_t late = 0;         ///< of those, stamped anew by the merger
        double late_until = 0;   ///< the last stamp given to a late one (data time [s]), or 0
        size_t repeats = 0;      ///< sent again after they had arrived (dropped)
        size_t out_of_turn = 0;  ///< arrived after a gap (dropped; sent again by the node)
        size_t connections = 0;  ///< hellos: the node's start and each restart
        bool finished = false;   ///< its last reading arrived
        std::vector<double> latencies;  ///< per reading: send to end of its filter step [s]
    };

    /** Binds `endpoint`. \throw std::runtime_error "<endpoint>: cannot listen: <why>" */
    TeamListener(const std::string& endpoint, std::vector<std::string> robots, TOptions options);
    ~TeamListener() override;

    bool next(core::TRawlogEntry& entry) override;
    /// What arrived (complete once next() returned false).
    const core::TRawlogSummary& summary() const override;
    const std::string& file() const override;
    void stepFinished() override;

    /// Per robot of the team (complete once next() returned false).
    const std::vector<TRobotStats>& stats() const;
    /** Per robot: readings, late, late_until (null if none), repeats, out_of_turn, connections,
     *  finished, latency_mean_s, latency_p95_s, latency_max_s; and the windows, window_expiries
     *  and ended_by_idle_timeout: as a JSON object. */
    std::string statsJson() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace mrpt_vslam::team
