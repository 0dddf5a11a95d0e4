#pragma once

#include <mrpt/core/Clock.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/system/datetime.h>

#include <cstdint>
#include <string>
#include <vector>

namespace mrpt_vslam::team {

/** One message between a robot node (vslam-robot-node) and the mapper (multirobot-vslam
 *  --listen), as bytes of an MRPT archive (doc/team-online.md):
 *  - Hello (node → mapper): `robot` asks where to go on; `data_time`: its first reading's time;
 *  - Welcome (mapper → node): `seq`, the next reading the mapper expects of the robot, and the
 *    team's clock that paces every node: data time `data_time` at the mapper's wall time
 *    `sent_time` (set by the first hello the mapper got);
 *  - Reading (node → mapper): the robot's reading number `seq` (0, 1, ...), an MRPT observation
 *    with its timestamp, `sent_time` (the node's wall clock), and `watermark`: the node sends no
 *    reading older than it after this one (the time of its next reading; after the last one
 *    kNoMoreReadings);
 *  - Ack (mapper → node): every reading before `seq` arrived;
 *  - End (node → mapper): the robot has `seq` readings in all;
 *  - Done (mapper → node): all of them arrived; the node may stop.
 *  Data times are MRPT timestamps, sent exactly; `sent_time` is seconds since the Unix epoch. */
struct TTeamMessage {
    enum class Type : uint8_t { Hello = 1, Welcome, Reading, Ack, End, Done };

    Type type = Type::Hello;
    std::string robot;
    uint64_t seq = 0;
    mrpt::Clock::time_point data_time = INVALID_TIMESTAMP;
    double sent_time = 0;
    mrpt::Clock::time_point watermark = INVALID_TIMESTAMP;
    mrpt::obs::CObservation::Ptr observation;  ///< Reading only

    std::vector<uint8_t> encode() const;
    /** \throw std::runtime_error for bytes that are no message of this version. */
    static TTeamMessage decode(const void* data, size_t size);
};

/// The watermark of a robot's last reading.
constexpr mrpt::Clock::time_point kNoMoreReadings = mrpt::Clock::time_point::max();

/// The wall clock, seconds since the Unix epoch.
double wallClockNow();

}  // namespace mrpt_vslam::team
