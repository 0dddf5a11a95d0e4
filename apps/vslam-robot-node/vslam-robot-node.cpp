// vslam-robot-node: plays one robot's part of a team rawlog to the mapper (multirobot-vslam
// --listen) over ZeroMQ, as the robot would send it live (doc/team-online.md).
#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/TclapParse.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/core/Version.h>
#include <mrpt_vslam/multirobot/registerAllClasses.h>
#include <mrpt_vslam/team/RobotNode.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace mrpt_vslam;

/** The observations of `robot` (labels `<robot>_...`) of an observation-only rawlog, in the
 *  rawlog's order. \throw std::runtime_error naming the file when there are none, when the rawlog
 *  holds actions or sensory frames, or when they go back in time */
std::vector<mrpt::obs::CObservation::Ptr> readingsOf(const std::string& file,
                                                     const std::string& robot)
{
    core::RawlogReader reader(file);
    std::vector<mrpt::obs::CObservation::Ptr> readings;
    const std::string prefix = robot + "_";
    for (core::TRawlogEntry e; reader.next(e);) {
        if (e.actions || e.observations)
            throw std::runtime_error(file +
                                     ": holds action collections or sensory frames; a robot node "
                                     "plays observation-only rawlogs (<ROBOT>_... labels)");
        if (!e.observation || e.observation->sensorLabel.rfind(prefix, 0) != 0) continue;
        if (!readings.empty() && e.observation->timestamp < readings.back()->timestamp)
            throw std::runtime_error(file + ": entry " + std::to_string(e.index) + " (" +
                                     e.observation->sensorLabel + ") is older than the one before");
        readings.push_back(e.observation);
    }
    if (readings.empty())
        throw std::runtime_error(file + ": no readings labelled " + prefix +
                                 "...; the rawlog has: " + reader.summary().describe());
    return readings;
}

}  // namespace

int main(int argc, char** argv)
{
    const std::string app = "vslam-robot-node";
    try {
        TCLAP::CmdLine cmd(
            "Plays one robot's readings (labels <ROBOT>_...) of an observation-only rawlog to a "
            "mapper (multirobot-vslam --listen) over ZeroMQ, paced by their timestamps; keeps "
            "each reading until the mapper has it, so that a dropped link or a restart loses "
            "none (doc/team-online.md).",
            ' ', core::projectVersion());
        TCLAP::UnlabeledValueArg<std::string> rawlog("RAWLOG", "The team's rawlog.", true, "",
                                                     "RAWLOG", cmd);
        TCLAP::ValueArg<std::string> robot("", "robot", "The robot to play, e.g. R1.", true, "",
                                           "ROBOT", cmd);
        TCLAP::ValueArg<std::string> connect("", "connect",
                                             "The mapper's address, e.g. tcp://localhost:5555.",
                                             true, "", "ENDPOINT", cmd);
        TCLAP::ValueArg<double> rate("", "rate", "Pace: times real time (default 1).", false, 1,
                                     "X", cmd);
        TCLAP::ValueArg<double> giveUp(
            "", "give-up-after",
            "Stop with an error when the mapper has not answered for this long [s]; 0 (default): "
            "wait for it.",
            false, 0, "S", cmd);
        TCLAP::SwitchArg quiet("q", "quiet", "No progress line.", cmd, false);
        std::string message;
        if (core::parseTclap(cmd, argc, argv, app, message) != core::TclapOutcome::Parsed) {
            std::cout << message;  // --help or --version
            return 0;
        }
        if (!(rate.getValue() > 0 && std::isfinite(rate.getValue())))
            throw core::UsageError("--rate must be > 0 (see " + app + " --help)");
        if (!(giveUp.getValue() >= 0 && std::isfinite(giveUp.getValue())))
            throw core::UsageError("--give-up-after must be >= 0 (see " + app + " --help)");

        multirobot::registerAllClasses_multirobot();  // the classes a team rawlog may hold
        const auto readings = readingsOf(rawlog.getValue(), robot.getValue());
        team::RobotNode::TOptions options;
        options.rate = rate.getValue();
        options.give_up_after_s = giveUp.getValue();
        options.quiet = quiet.getValue();
        team::RobotNode node(robot.getValue(), connect.getValue(), options);
        const auto stats = node.play(readings);
        if (!quiet.getValue())
            std::printf(
                "%s: %s: %zu readings (%zu the mapper had already), %zu sent, %zu resends\n",
                app.c_str(), robot.getValue().c_str(), stats.readings, stats.skipped, stats.sent,
                stats.resends);
        return 0;
    } catch (const core::UsageError& e) {
        std::cerr << app << ": error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << app << ": error: " << core::oneLineMessage(e) << "\n";
        return 1;
    }
}
