#pragma once

#include <mrpt/obs/CObservation.h>

#include <cstddef>
#include <string>
#include <vector>

namespace mrpt_vslam::team {

/** A robot's end of the team link (doc/team-online.md): connects a ZeroMQ DEALER socket to the
 *  mapper (TeamListener) and sends the robot's readings, paced by their timestamps.
 *  - On (re)start it says hello and the mapper answers with the first reading it still needs
 *    and the time its stream has reached; readings older than that go at once, the rest at
 *    `rate` times their own pace from there.
 *  - It keeps every reading until the mapper acknowledges it; while the mapper is unreachable
 *    they wait, and when no acknowledgement has come for `resend_after_s` it sends again from
 *    the first one not acknowledged. So a reading is lost neither to a dropped link nor to a
 *    restart of the node.
 *  - It returns when the mapper has every reading (or throws if `give_up_after_s` > 0 passes
 *    with no word from the mapper). */
class RobotNode {
  public:
    struct TOptions {
        double rate = 1;              ///< pace: this many times real time (> 0)
        double resend_after_s = 1.0;  ///< send again when no acknowledgement came this long
        double give_up_after_s = 0;   ///< 0: wait for the mapper for ever
        bool quiet = false;           ///< no progress line
    };
    /// What was sent.
    struct TStats {
        size_t readings = 0;  ///< the robot's readings
        size_t skipped = 0;   ///< the mapper had them already (restart)
        size_t sent = 0;      ///< messages with a reading, repeats included
        size_t resends = 0;   ///< times it went back to the first unacknowledged reading
    };

    RobotNode(std::string robot, std::string endpoint, TOptions options);

    /** Sends `readings` (the robot's, in time order) as above.
     *  \throw std::runtime_error naming the endpoint on a transport error or when giving up */
    TStats play(const std::vector<mrpt::obs::CObservation::Ptr>& readings);

  private:
    std::string m_robot, m_endpoint;
    TOptions m_options;
};

}  // namespace mrpt_vslam::team
