#include <mrpt_vslam/team/Endpoint.h>

#include <algorithm>
#include <cctype>
#include <stdexcept>

namespace mrpt_vslam::team {

void requireValidTcpPort(const std::string& endpoint)
{
    const std::string tcp = "tcp://";
    if (endpoint.rfind(tcp, 0) != 0) return;
    const size_t colon = endpoint.rfind(':');
    if (colon < tcp.size()) return;  // no port: ZeroMQ's own error
    const std::string port = endpoint.substr(colon + 1);
    if (port == "*") return;
    const bool digits =
        !port.empty() && port.size() <= 5 &&
        std::all_of(port.begin(), port.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
    if (!digits || std::stoul(port) > 65535)
        throw std::invalid_argument("port " + port + " is not a number from 0 to 65535");
}

}  // namespace mrpt_vslam::team
