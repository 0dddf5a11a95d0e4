#pragma once

#include <string>

namespace mrpt_vslam::team {

/** Throws std::invalid_argument "port P is not a number from 0 to 65535" for a ZeroMQ `tcp://`
 *  address whose port is neither `*` nor such a number: ZeroMQ would take it modulo 65536 without
 *  an error (port 99999 of all interfaces listens at 34463). Other transports pass. */
void requireValidTcpPort(const std::string& endpoint);

}  // namespace mrpt_vslam::team
