#include <mrpt/core/format.h>
#include <mrpt_vslam/team/Endpoint.h>
#include <mrpt_vslam/team/RobotNode.h>
#include <mrpt_vslam/team/TeamMessage.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <zmq.hpp>

namespace mrpt_vslam::team {

RobotNode::RobotNode(std::string robot, std::string endpoint, TOptions options)
    : m_robot(std::move(robot)), m_endpoint(std::move(endpoint)), m_options(options)
{
    if (!(m_options.rate > 0)) throw std::invalid_argument("rate must be > 0");
}

RobotNode::TStats RobotNode::play(const std::vector<mrpt::obs::CObservation::Ptr>& readings)
{
    zmq::context_t context;
    zmq::socket_t socket(context, zmq::socket_type::dealer);
    socket.set(zmq::sockopt::linger, 0);
    try {
        requireValidTcpPort(m_endpoint);
        socket.connect(m_endpoint);
    } catch (const std::exception& e) {
        throw std::runtime_error(m_endpoint + ": cannot connect: " + e.what());
    }
    const auto send = [&](TTeamMessage m) {
        m.robot = m_robot;
        m.sent_time = wallClockNow();
        if (m.type == TTeamMessage::Type::Hello && !readings.empty())
            m.data_time = readings.front()->timestamp;
        const auto bytes = m.encode();
        // a full queue (the mapper away for long) waits for the next round
        (void)socket.send(zmq::buffer(bytes), zmq::send_flags::dontwait);
    };
    const size_t n = readings.size();
    TStats stats;
    stats.readings = n;

    bool welcomed = false, done = false;
    size_t acked = 0, nextToSend = 0;
    double wallStart = 0;  // the pace: reading time t goes at wallStart + (t - dataStart) / rate
    double dataStart = 0;
    double lastWord = wallClockNow(), lastProgress = lastWord, lastLine = 0;
    double lastHello = -1e9, lastEnd = -1e9;
    const auto timeOf = [&](size_t i) { return mrpt::Clock::toDouble(readings[i]->timestamp); };
    const auto dueAt = [&](size_t i) {
        return wallStart + (timeOf(i) - dataStart) / m_options.rate;
    };

    while (!done) {
        double now = wallClockNow();
        if (!welcomed && now - lastHello > m_options.resend_after_s) {
            TTeamMessage hello;
            hello.type = TTeamMessage::Type::Hello;
            send(hello);
            lastHello = now;
        }
        if (welcomed) {
            while (nextToSend < n && dueAt(nextToSend) <= now) {
                if (acked == nextToSend) lastProgress = now;  // the wait for an ack starts
                TTeamMessage m;
                m.type = TTeamMessage::Type::Reading;
                m.seq = nextToSend;
                m.observation = readings[nextToSend];
                m.watermark =
                    nextToSend + 1 < n ? readings[nextToSend + 1]->timestamp : kNoMoreReadings;
                send(m);
                stats.sent++;
                nextToSend++;
            }
            if (nextToSend == n && acked == n && now - lastEnd > m_options.resend_after_s) {
                TTeamMessage end;  // said again until the mapper is done
                end.type = TTeamMessage::Type::End;
                end.seq = n;
                send(end);
                lastEnd = now;
            }
            if (acked < nextToSend && now - lastProgress > m_options.resend_after_s) {
                nextToSend = acked;  // go back to the first reading not acknowledged
                stats.resends++;
                lastProgress = now;
                continue;
            }
        }
        // wait for the mapper's word until the next reading is due
        double wait = 0.1;
        if (welcomed && nextToSend < n) wait = std::clamp(dueAt(nextToSend) - now, 0.0, wait);
        std::vector<zmq::pollitem_t> items{{socket.handle(), 0, ZMQ_POLLIN, 0}};
        zmq::poll(items, std::chrono::milliseconds(static_cast<long>(wait * 1e3)));
        for (zmq::message_t msg; socket.recv(msg, zmq::recv_flags::dontwait);) {
            TTeamMessage m;
            try {
                m = TTeamMessage::decode(msg.data(), msg.size());
            } catch (const std::runtime_error&) {
                continue;  // not the mapper's
            }
            lastWord = wallClockNow();
            if (m.type == TTeamMessage::Type::Done) {
                done = true;
            } else if (m.type == TTeamMessage::Type::Welcome && !welcomed) {
                welcomed = true;
                acked = nextToSend = std::min<size_t>(m.seq, n);
                stats.skipped = acked;
                // the team's clock: readings it has passed go at once
                wallStart = m.sent_time;
                dataStart = mrpt::Clock::toDouble(m.data_time);
                lastProgress = lastWord;
            } else if (m.type == TTeamMessage::Type::Ack && m.seq > acked && m.seq <= n) {
                acked = m.seq;
                lastProgress = lastWord;
            }
        }
        now = wallClockNow();
        if (m_options.give_up_after_s > 0 && now - lastWord > m_options.give_up_after_s)
            throw std::runtime_error(m_endpoint + ": no word from the mapper for " +
                                     mrpt::format("%g", m_options.give_up_after_s) + " s");
        if (!m_options.quiet && welcomed && now - lastLine >= 1) {
            lastLine = now;
            std::fprintf(stderr, "\r%s: %zu of %zu readings sent, %zu acknowledged",
                         m_robot.c_str(), nextToSend, n, acked);
        }
    }
    if (!m_options.quiet) std::fprintf(stderr, "\n");
    return stats;
}

}  // namespace mrpt_vslam::team
