#include <gtest/gtest.h>
#include <mrpt_vslam/team/Endpoint.h>

#include <stdexcept>
#include <string>

using mrpt_vslam::team::requireValidTcpPort;

TEST(Endpoint, TcpPortsOutsideZeroToFFFFAreRefused)
{
    for (const char* ok : {"tcp://*:5555", "tcp://127.0.0.1:0", "tcp://[::1]:65535", "tcp://*:*",
                           "tcp://localhost:00080", "ipc:///tmp/mapper", "inproc://mapper"})
        EXPECT_NO_THROW(requireValidTcpPort(ok)) << ok;
    for (const auto& [endpoint, port] :
         {std::pair<std::string, std::string>{"tcp://*:65536", "65536"},
          {"tcp://*:99999", "99999"},
          {"tcp://*:123456", "123456"},
          {"tcp://*:-1", "-1"},
          {"tcp://*:55a5", "55a5"},
          {"tcp://127.0.0.1:", ""}}) {
        try {
            requireValidTcpPort(endpoint);
            ADD_FAILURE() << endpoint;
        } catch (const std::invalid_argument& e) {
            EXPECT_EQ(std::string(e.what()), "port " + port + " is not a number from 0 to 65535");
        }
    }
}
