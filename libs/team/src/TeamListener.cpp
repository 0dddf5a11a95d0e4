#include <mrpt_vslam/team/Endpoint.h>
#include <mrpt_vslam/team/ReadingMerger.h>
#include <mrpt_vslam/team/TeamListener.h>
#include <mrpt_vslam/team/TeamMessage.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <iterator>
#include <mutex>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <zmq.hpp>
#include <zmq_addon.hpp>

namespace mrpt_vslam::team {

struct TeamListener::Impl {
    Impl(std::string address, std::vector<std::string> robots, TOptions o)
        : endpoint(std::move(address)),
          options(o),
          merger(robots, o.reorder_window_s, o.join_window_s),
          socket(context, zmq::socket_type::router),
          stats(robots.size()),
          expected(robots.size(), 0),
          identity(robots.size())
    {
        socket.set(zmq::sockopt::linger, 0);
        try {
            requireValidTcpPort(endpoint);
            socket.bind(endpoint);
        } catch (const std::exception& e) {
            throw std::runtime_error(endpoint + ": cannot listen: " + e.what());
        }
        lastMessage = wallClockNow();
        receiver = std::thread([this] {
            try {
                while (!stopping) receive(0.05);
            } catch (const std::exception& e) {  // next() reports it
                {
                    const std::lock_guard lock(mutex);
                    failure = e.what();
                }
                arrived.notify_one();
            }
        });
    }
    ~Impl() { stop(); }
    /// Ends the receiving thread: nothing changes after it.
    void stop()
    {
        stopping = true;
        if (receiver.joinable()) receiver.join();
    }

    std::string endpoint;
    TOptions options;
    /// The merger and the counts, shared by the receiving thread and next()
    std::mutex mutex;
    std::condition_variable arrived;
    ReadingMerger merger;
    zmq::context_t context;
    zmq::socket_t socket;  ///< the receiving thread's only
    std::vector<TRobotStats> stats;
    std::vector<uint64_t> expected;     ///< per robot: the next reading number it owes
    std::vector<std::string> identity;  ///< per robot: its node's latest ZeroMQ identity
    core::TRawlogSummary summary;
    size_t entries = 0;
    double lastMessage = 0;
    /// The team's clock (TTeamMessage): data time `clockData` at wall time `clockWall`.
    mrpt::Clock::time_point clockData = INVALID_TIMESTAMP;
    double clockWall = 0;
    bool ended = false;
    bool timedOut = false;
    /// Readings handed out and not yet in a finished step: (robot, sent time).
    std::vector<std::pair<size_t, double>> unfused;
    /// The time of the last time barrier handed out, and whether it was the last entry.
    mrpt::Clock::time_point barrierAt = INVALID_TIMESTAMP;
    bool lastWasBarrier = false;
    std::atomic<bool> stopping{false};
    std::string failure;   ///< what stopped the receiving thread
    std::thread receiver;  ///< takes and acknowledges messages while the filter runs

    void send(size_t robot, const TTeamMessage& m)
    {
        if (identity[robot].empty()) return;
        const auto bytes = m.encode();
        socket.send(zmq::buffer(identity[robot]), zmq::send_flags::sndmore);
        socket.send(zmq::buffer(bytes), zmq::send_flags::none);
    }
    /// Takes every message waiting, for up to `timeout_s` for the first one (receiving thread).
    void receive(double timeout_s);
    void handle(const std::string& from, const TTeamMessage& m, std::set<size_t>& acks);
};

void TeamListener::Impl::handle(const std::string& from, const TTeamMessage& m,
                                std::set<size_t>& acks)
{
    const auto r = merger.robotIndex(m.robot);
    if (!r) {
        if (!options.quiet)
            std::fprintf(stderr, "%s: a node for robot '%s', which is not in the team, ignored\n",
                         endpoint.c_str(), m.robot.c_str());
        return;
    }
    identity[*r] = from;
    auto& s = stats[*r];
    switch (m.type) {
        case TTeamMessage::Type::Hello: {
            s.connections++;
            if (!options.quiet)
                std::fprintf(stderr, "%s: robot %s connected (from its reading %llu)\n",
                             endpoint.c_str(), m.robot.c_str(),
                             static_cast<unsigned long long>(expected[*r]));
            if (clockData == INVALID_TIMESTAMP) {  // the first node sets the team's clock
                clockData = m.data_time;
                clockWall = wallClockNow();
            }
            TTeamMessage w;
            w.type = s.finished ? TTeamMessage::Type::Done : TTeamMessage::Type::Welcome;
            w.robot = m.robot;
            w.seq = expected[*r];
            w.data_time = clockData;
            w.sent_time = clockWall;
            send(*r, w);
            break;
        }
        case TTeamMessage::Type::Reading:
            if (m.seq < expected[*r]) {
                s.repeats++;
            } else if (m.seq > expected[*r]) {
                s.out_of_turn++;
            } else if (!s.finished) {
                summary.add(*m.observation);
                summary.objects++;
                merger.add(*r, m.observation, m.watermark, m.sent_time, wallClockNow());
                expected[*r]++;
                s.readings++;
            }
            acks.insert(*r);
            break;
        case TTeamMessage::Type::End:
            if (m.seq == expected[*r] && !s.finished) {
                s.finished = true;
                merger.finish(*r);
            }
            if (s.finished) {
                TTeamMessage d;
                d.type = TTeamMessage::Type::Done;
                d.robot = m.robot;
                d.seq = expected[*r];
                send(*r, d);
            } else {
                acks.insert(*r);
            }
            break;
        default:
            break;  // messages of the mapper's kind are not for it
    }
}

void TeamListener::Impl::receive(double timeout_s)
{
    std::vector<zmq::pollitem_t> items{{socket.handle(), 0, ZMQ_POLLIN, 0}};
    const auto ms = std::chrono::milliseconds(static_cast<long>(std::max(0.0, timeout_s) * 1e3));
    if (zmq::poll(items, ms) <= 0) return;
    std::set<size_t> acks;
    std::unique_lock lock(mutex);
    for (;;) {
        std::vector<zmq::message_t> parts;
        if (!zmq::recv_multipart(socket, std::back_inserter(parts), zmq::recv_flags::dontwait))
            break;
        lastMessage = wallClockNow();
        if (parts.size() != 2) continue;  // not a node of ours
        try {
            handle(parts[0].to_string(), TTeamMessage::decode(parts[1].data(), parts[1].size()),
                   acks);
        } catch (const std::runtime_error& e) {
            if (!options.quiet) std::fprintf(stderr, "%s: %s\n", endpoint.c_str(), e.what());
        }
    }
    for (const size_t r : acks) {
        TTeamMessage a;
        a.type = TTeamMessage::Type::Ack;
        a.robot = merger.robots()[r];
        a.seq = expected[r];
        send(r, a);
    }
    lock.unlock();
    arrived.notify_one();
}

TeamListener::TeamListener(const std::string& endpoint, std::vector<std::string> robots,
                           TOptions options)
    : m_impl(std::make_unique<Impl>(endpoint, std::move(robots), options))
{
}

TeamListener::~TeamListener() = default;

bool TeamListener::next(core::TRawlogEntry& entry)
{
    auto& d = *m_impl;
    std::unique_lock lock(d.mutex);
    for (;;) {
        if (!d.failure.empty()) throw std::runtime_error(d.endpoint + ": " + d.failure);
        const double now = wallClockNow();
        if (auto r = d.merger.next(now)) {
            entry = core::TRawlogEntry();
            entry.observation = r->observation;
            entry.timestamp = r->observation->timestamp;
            entry.index = d.entries++;
            if (r->late) {
                d.stats[r->robot].late++;
                d.stats[r->robot].late_until = mrpt::Clock::toDouble(entry.timestamp);
            }
            d.unfused.emplace_back(r->robot, r->sent_time);
            d.lastWasBarrier = false;
            return true;
        }
        // the stream's time is complete: its step need not wait for a later reading
        const auto t = d.merger.streamTime();
        if (t != INVALID_TIMESTAMP && t != d.barrierAt && d.merger.settled(t)) {
            entry = core::TRawlogEntry();
            entry.time_barrier = true;
            entry.timestamp = t;
            entry.index = d.entries++;
            d.barrierAt = t;
            d.lastWasBarrier = true;
            return true;
        }
        if (d.merger.done()) {
            d.ended = true;
            lock.unlock();
            d.stop();
            return false;
        }
        if (now - d.lastMessage > d.options.idle_timeout_s) {
            // robots that stopped without a word: what came of them is all there is
            d.timedOut = true;
            for (size_t r = 0; r < d.stats.size(); r++)
                if (!d.merger.finished(r)) d.merger.finish(r);
            if (!d.options.quiet)
                std::fprintf(stderr, "%s: no message for %g s: ending the run\n",
                             d.endpoint.c_str(), d.options.idle_timeout_s);
            continue;
        }
        double wait = 0.1;
        if (const auto deadline = d.merger.deadline())
            wait = std::clamp(*deadline - now, 0.0, wait);
        d.arrived.wait_for(lock, std::chrono::duration<double>(wait));
    }
}

void TeamListener::stepFinished()
{
    auto& d = *m_impl;
    const std::lock_guard lock(d.mutex);
    const double now = wallClockNow();
    // the last reading handed out opened the next step, unless the data ended or a time barrier
    // closed the step
    const size_t fused =
        d.ended || d.lastWasBarrier || d.unfused.empty() ? d.unfused.size() : d.unfused.size() - 1;
    for (size_t i = 0; i < fused; i++)
        d.stats[d.unfused[i].first].latencies.push_back(now - d.unfused[i].second);
    d.unfused.erase(d.unfused.begin(), d.unfused.begin() + static_cast<std::ptrdiff_t>(fused));
}

const core::TRawlogSummary& TeamListener::summary() const { return m_impl->summary; }

const std::string& TeamListener::file() const { return m_impl->endpoint; }

const std::vector<TeamListener::TRobotStats>& TeamListener::stats() const { return m_impl->stats; }

std::string TeamListener::statsJson() const
{
    auto& d = *m_impl;
    const std::lock_guard lock(d.mutex);
    std::ostringstream j;
    j.precision(6);
    j << "{\"address\": \"" << d.endpoint
      << "\", \"reorder_window_s\": " << d.options.reorder_window_s
      << ", \"join_window_s\": " << d.options.join_window_s
      << ", \"window_expiries\": " << d.merger.windowExpiries()
      << ", \"ended_by_idle_timeout\": " << (d.timedOut ? "true" : "false") << ", \"robots\": {";
    for (size_t r = 0; r < d.stats.size(); r++) {
        const auto& s = d.stats[r];
        auto lat = s.latencies;
        std::sort(lat.begin(), lat.end());
        const double mean =
            lat.empty() ? 0 : std::accumulate(lat.begin(), lat.end(), 0.0) / lat.size();
        const auto quantile = [&](double q) {
            return lat.empty() ? 0
                               : lat[std::min(lat.size() - 1, static_cast<size_t>(q * lat.size()))];
        };
        j << (r ? ", " : "") << "\"" << d.merger.robots()[r] << "\": {\"readings\": " << s.readings
          << ", \"late\": " << s.late << ", \"late_until\": ";
        if (s.late > 0)
            j << std::to_string(s.late_until);  // full precision of a timestamp
        else
            j << "null";
        j << ", \"repeats\": " << s.repeats << ", \"out_of_turn\": " << s.out_of_turn
          << ", \"connections\": " << s.connections
          << ", \"finished\": " << (s.finished ? "true" : "false")
          << ", \"latency_mean_s\": " << mean << ", \"latency_p95_s\": " << quantile(0.95)
          << ", \"latency_max_s\": " << (lat.empty() ? 0 : lat.back()) << "}";
    }
    j << "}}";
    return j.str();
}

}  // namespace mrpt_vslam::team
