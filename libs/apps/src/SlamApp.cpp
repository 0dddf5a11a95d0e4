#include "SlamApp.h"

#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/system/filesystem.h>
#include <mrpt_vslam/core/ActionFrameSource.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/ProcessMemory.h>
#include <mrpt_vslam/core/ProgressReporter.h>
#include <mrpt_vslam/core/RunEvaluation.h>
#include <mrpt_vslam/core/RunOutputs.h>
#include <mrpt_vslam/core/SceneFraming.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <opencv2/core/version.hpp>
#include <stdexcept>

namespace mrpt_vslam::apps {

std::string poseJsonArray(const mrpt::poses::CPose3D& pose)
{
    return mrpt::format("[%g, %g, %g, %g, %g, %g]", pose.x(), pose.y(), pose.z(),
                        mrpt::RAD2DEG(pose.yaw()), mrpt::RAD2DEG(pose.pitch()),
                        mrpt::RAD2DEG(pose.roll()));
}

std::string poseText(const mrpt::poses::CPose3D& pose)
{
    return mrpt::format("x %g, y %g, z %g m, yaw %g, pitch %g, roll %g deg", pose.x(), pose.y(),
                        pose.z(), mrpt::RAD2DEG(pose.yaw()), mrpt::RAD2DEG(pose.pitch()),
                        mrpt::RAD2DEG(pose.roll()));
}

void reportSensorPoseChecks(const char* app, const char* read, const char* doc,
                            const std::vector<TSensorCheck>& checks, double seconds,
                            core::RunReport& report, bool quiet)
{
    // A turn of 3° or more, or a move of 0.15 m or more, 5 σ or more from 0 (a move: 5 times
    // its largest σ), warns, where the path tells the two apart (turn confounding < 4; 33-58 on
    // the circles of tests/multirobot_vslam_test.cpp). Correct sensors give turns of up to 1.4°
    // on the simulated teams (their odometry's heading drift), moves of 0.3-0.5 m at 1-2 σ on
    // MRCLAM (doc/results/sensor-pose-check.md). A pitch or roll of 1° or more at 5 σ warns
    // too: correct cameras give up to 0.4° on the simulated teams, and a forward camera pitched
    // by 2° more than stated can put a path several times as far from the truth. So does a
    // height 0.1 m or more off another sensor's, at 5 σ or more, over 10 or more landmarks
    // (doc/results/sensor-pose-check.md). A scale of the readings 5 % or more from 1 at 5 σ or
    // more warns: correct sensors give 1.00 to 1.02 on the simulated teams.
    constexpr double kTurnDeg = 3, kMove = 0.15, kSigmas = 5, kConfounding = 4, kTiltDeg = 1,
                     kHeight = 0.1, kScale = 0.05;
    constexpr size_t kHeightLandmarks = 10;
    report.setPartTiming("sensor_pose_check", seconds);
    std::string json;
    // per sensor: its line, what it is warned of, and the sensors its heights are off from
    enum class TWarning { none, pose, scale, tilt };
    struct TVerdict {
        std::string sensor, fit;
        TWarning warning;
        std::vector<std::string> heightsOffFrom;
    };
    std::vector<TVerdict> verdicts;
    for (const auto& [sensor, d, tilt, heights] : checks) {
        const double turnDeg = mrpt::RAD2DEG(d.delta[2]),
                     turnStdDeg = mrpt::RAD2DEG(std::sqrt(d.cov(2, 2)));
        const Eigen::Vector2d t = d.delta.head<2>();
        const double turnConfounding = d.turnConfounding();
        const bool scaleTold = d.scaleTold();
        json += mrpt::format(
            "%s\"%s\": {\"pairs\": %zu, \"pairs_beyond_3_sigma\": %zu, \"dx_dy_m\": [%s, %s], "
            "\"std_dx_dy_m\": [%s, %s], \"dyaw_deg\": %s, \"std_dyaw_deg\": %s, "
            "\"dyaw_confounding\": %s, \"range_scale\": %s, \"std_range_scale\": %s, "
            "\"range_scale_confounding\": %s",
            json.empty() ? "" : ", ", sensor.c_str(), d.pairs, d.outlier_pairs,
            core::jsonNumber(t[0], 4).c_str(), core::jsonNumber(t[1], 4).c_str(),
            core::jsonNumber(std::sqrt(d.cov(0, 0)), 4).c_str(),
            core::jsonNumber(std::sqrt(d.cov(1, 1)), 4).c_str(),
            core::jsonNumber(turnDeg, 3).c_str(), core::jsonNumber(turnStdDeg, 3).c_str(),
            core::jsonNumber(turnConfounding, 2).c_str(),
            (scaleTold ? core::jsonNumber(d.scale, 4) : "null").c_str(),
            (scaleTold ? core::jsonNumber(d.scale_std, 4) : "null").c_str(),
            core::jsonNumber(d.scale_confounding, 2).c_str());
        const std::string scaleFit =
            scaleTold
                ? mrpt::format(" read at %.3f (std %.3f) times their range", d.scale, d.scale_std)
                : "";
        // on a path of one curvature the fit is a point of a ridge, picked by the noise
        const bool toldApart = turnConfounding < kConfounding;
        std::string fit =
            toldApart
                ? mrpt::format(
                      "its readings of %s from nearby steps fit best with the sensor turned by "
                      "%.1f deg (std %.1f) and moved by (%.2f, %.2f) m (std %.2f, %.2f)%s%s, %zu "
                      "of %zu pairs beyond 3 sigma",
                      read, turnDeg, turnStdDeg, t[0], t[1], std::sqrt(d.cov(0, 0)),
                      std::sqrt(d.cov(1, 1)), scaleTold ? " and" : "", scaleFit.c_str(),
                      d.outlier_pairs, d.pairs)
                : mrpt::format(
                      "its readings of %s from nearby steps cannot tell a turn of the sensor from "
                      "a move on this path (of one curvature throughout: a circle), so its yaw "
                      "and position are not checked; %s%zu of %zu pairs beyond 3 sigma",
                      read, scaleTold ? ("they fit best" + scaleFit + "; ").c_str() : "",
                      d.outlier_pairs, d.pairs);
        const bool turned =
            std::abs(turnDeg) >= kTurnDeg && std::abs(turnDeg) >= kSigmas * turnStdDeg;
        const bool moved = t.norm() >= kMove && t.norm() >= kSigmas * d.largestMoveStd();
        const bool scaled = scaleTold && std::abs(d.scale - 1) >= kScale &&
                            std::abs(d.scale - 1) >= kSigmas * d.scale_std;
        bool tilted = false;
        if (tilt) {
            const Eigen::Vector2d deg = tilt->delta * (180 / M_PI),
                                  stdDeg = tilt->cov.diagonal().cwiseSqrt() * (180 / M_PI);
            json += mrpt::format(
                ", \"tilt_landmarks\": %zu, \"tilt_readings\": %zu, "
                "\"tilt_readings_beyond_3_sigma\": %zu, \"dpitch_droll_deg\": [%s, %s], "
                "\"std_dpitch_droll_deg\": [%s, %s]",
                tilt->points, tilt->readings, tilt->outlier_readings,
                core::jsonNumber(deg[0], 3).c_str(), core::jsonNumber(deg[1], 3).c_str(),
                core::jsonNumber(stdDeg[0], 3).c_str(), core::jsonNumber(stdDeg[1], 3).c_str());
            fit += mrpt::format(
                "; the heights of its readings of %zu landmarks fit best with it pitched by %.1f "
                "deg (std %.1f) and rolled by %.1f deg (std %.1f), %zu of %zu readings beyond 3 "
                "sigma",
                tilt->points, deg[0], stdDeg[0], deg[1], stdDeg[1], tilt->outlier_readings,
                tilt->readings);
            for (int i = 0; i < 2; i++)
                tilted |= std::abs(deg[i]) >= kTiltDeg && std::abs(deg[i]) >= kSigmas * stdDeg[i];
        }
        std::string heightJson;
        std::vector<std::string> offFrom;
        for (const auto& [other, h] : heights) {
            heightJson += mrpt::format(
                "%s\"%s\": {\"landmarks\": %zu, \"dz_m\": %s, \"std_dz_m\": %s}",
                heightJson.empty() ? "" : ", ", other.c_str(), h.points,
                core::jsonNumber(h.dz, 4).c_str(), core::jsonNumber(h.std_dz, 4).c_str());
            fit += mrpt::format(
                "; the %zu landmarks it shares with %s lie %.2f m (std %.2f) %s in its readings",
                h.points, other.c_str(), std::abs(h.dz), h.std_dz, h.dz >= 0 ? "higher" : "lower");
            if (h.points >= kHeightLandmarks && std::abs(h.dz) >= kHeight &&
                std::abs(h.dz) >= kSigmas * h.std_dz)
                offFrom.push_back(other);
        }
        if (!heightJson.empty()) json += ", \"heights_against\": {" + heightJson + "}";
        json += "}";
        if (!quiet) std::printf("%s: %s: %s\n", app, sensor.c_str(), fit.c_str());
        // with the pose and noise right, about 1 pair in 90 lies beyond 3 σ
        const TWarning warning =
            ((turned || moved) && toldApart) || 10 * d.outlier_pairs > d.pairs ? TWarning::pose
            : scaled                                                           ? TWarning::scale
            : tilted ? TWarning::tilt  // the odometry plays no part in the tilt
                     : TWarning::none;
        verdicts.push_back({sensor, fit, warning, offFrom});
    }
    for (const auto& v : verdicts) {
        const auto warned = [&](const std::string& other) {
            for (const auto& w : verdicts)
                if (w.sensor == other) return w.warning != TWarning::none;
            return false;
        };
        if (v.warning == TWarning::pose)
            report.addWarning(v.sensor + ": " + v.fit +
                              ": check its pose on the robot and its noise (an odometry whose "
                              "heading drifts also looks like a turned sensor; " +
                              doc + ")");
        else if (v.warning == TWarning::scale)
            report.addWarning(v.sensor + ": " + v.fit +
                              ": check what gives its readings their scale (a stereo baseline, a "
                              "range unit) and the odometry's distances (" +
                              doc + ")");
        else if (v.warning == TWarning::tilt)
            report.addWarning(v.sensor + ": " + v.fit +
                              ": check its pitch and roll on the robot (" + doc + ")");
        else  // which of two is off, the heights do not tell; a wrong pose or tilt also moves them
            for (const auto& other : v.heightsOffFrom)
                if (!warned(other)) {
                    report.addWarning(v.sensor + ": " + v.fit +
                                      ": check its height on the robot, or that of " + other +
                                      " (" + doc + ")");
                    break;
                }
    }
    if (!json.empty()) report.setResultJson("sensor_pose_check", "{" + json + "}");
}

SlamApp::SlamApp(core::AppArguments arguments, std::string appName, std::string section)
    : name(std::move(appName)), args(std::move(arguments)), m_section(std::move(section))
{
    core::retainFreedMemory();
}

SlamApp::~SlamApp() = default;

core::UsageError SlamApp::usageError(const std::string& what) const
{
    return core::UsageError(cfg.name() + ": " + what);
}

core::UsageError SlamApp::configError(const std::exception& e) const
{
    if (!cfg.valueError().empty()) return core::UsageError(cfg.valueError());
    return usageError(core::oneLineMessage(e));
}

void SlamApp::initialize()
{
    cfg.loadFile(args.configFile, args.overrides);
    if (!cfg.sectionExists(m_section))
        for (const auto& other : {kOmniFastSLAMId, kMultiRobotVSLAMId, kViewSLAMId})
            if (other.name != name && cfg.sectionExists(other.section))
                throw usageError(std::string("a config of ") + other.name + " ([" + other.section +
                                 "]), not of " + name + " ([" + m_section + "])");
    rawlog = args.resolveRawlog(cfg, m_section);
    seed = args.resolveSeed(cfg, m_section);
    loadConfig();
    // [MotionModel]: MRPT's Gaussian model, used for observation-only rawlogs
    try {
        m_motionModel = core::ActionFrameSource::loadMotionModel(cfg, "MotionModel");
    } catch (const core::UsageError& e) {
        throw configError(e);
    }
    cfg.throwIfUnreadKeys();
    if (args.listen.empty() && std::filesystem::is_directory(rawlog))
        throw std::runtime_error(rawlog + ": cannot open rawlog (a folder)");
    if (args.listen.empty() && !mrpt::system::fileExists(rawlog))
        throw std::runtime_error(rawlog + ": cannot open rawlog");
    prepare();
    // a landmark file the results would be scored against stops the run before it starts
    if (const auto groundTruth = groundTruthName()) trueLandmarks(*groundTruth);
    if (args.gui) m_window = std::make_unique<LiveView>(name);
}

void SlamApp::startRun(const core::OutputDirectory&) {}

std::vector<std::string> SlamApp::odometryLabels() const { return {}; }

std::unique_ptr<core::RawlogEntrySource> SlamApp::openInput()
{
    return std::make_unique<core::RawlogReader>(rawlog);
}

void SlamApp::run()
{
    core::OutputDirectory out(args.outDir);
    for (const std::string& input : {args.configFile, rawlog})
        if (out.holdsRunFile(input))
            throw core::UsageError(input + ": a file the run writes in its folder " + out.path() +
                                   ": rename it, or choose another --out");
    out.removeEarlierRun();  // no file of an earlier run stands beside this one's
    core::RunTimer timer;
    try {
        const auto input = openInput();
        core::ProgressReporter progress(name, 0, args.quiet);
        startRun(out);
        core::ActionFrameSource source(*input, stepObservations(), m_motionModel, odometryLabels());
        // live, a robot with no reading since the last step (late, silent, behind) stands still
        if (!args.listen.empty()) source.standStillWithoutOdometry();
        mrpt::obs::CActionCollection::Ptr actions;
        mrpt::obs::CSensoryFrame::Ptr frame;
        while (source.next(actions, frame)) {
            m_odometryTiming = source.odometryTiming();
            step(actions, *frame, timer);
            input->stepFinished();
            progress.update(++steps);
            if (m_window)
                m_window->show([this](mrpt::opengl::COpenGLScene& scene) { drawLive(scene); });
        }
        m_odometryTiming = source.odometryTiming();
        progress.finish(steps);
        endSteps(input->summary());
        writeRunFolder(out, timer);
    } catch (const std::exception& e) {
        core::RunReport report(name);
        describeRun(report, timer);
        report.setFailed(core::oneLineMessage(e));
        report.write(out.file("run.json"));
        throw;
    }
    if (m_window && !args.quiet) m_window->waitUntilClosed();
}

double SlamApp::stepTime(mrpt::Clock::time_point stamp)
{
    const auto fail = [&](const std::string& what) {
        return std::runtime_error(rawlog + ": step " + std::to_string(steps) + what +
                                  ": the paths are stamped with the steps' times");
    };
    if (stamp == INVALID_TIMESTAMP) throw fail(" has no timestamp");
    if (m_lastStepStamp && stamp <= *m_lastStepStamp)
        throw fail(mrpt::format(" at %.6f s is not after step %zu at %.6f s",
                                mrpt::Clock::toDouble(stamp), steps - 1,
                                mrpt::Clock::toDouble(*m_lastStepStamp)));
    m_lastStepStamp = stamp;
    return mrpt::Clock::toDouble(stamp);
}

std::runtime_error SlamApp::noFramesError(const std::string& inputs,
                                          const core::TRawlogSummary& contents) const
{
    return std::runtime_error(rawlog + ": no frames with odometry and " + inputs +
                              " (action / sensory-frame pairs, or CObservationOdometry readings); "
                              "the rawlog has: " +
                              contents.describe());
}

double SlamApp::timedStep(core::RunTimer& timer, const std::string& where,
                          const std::function<void()>& update) const
{
    timer.startStep();
    try {
        update();
    } catch (const std::exception& e) {
        throw std::runtime_error(rawlog + ": " + where + ": " + core::oneLineMessage(e));
    }
    return timer.endStep();
}

void SlamApp::writeRunFolder(const core::OutputDirectory& out, const core::RunTimer& timer)
{
    core::RunReport report(name);
    mrpt::opengl::COpenGLScene scene;
    writeResults(out, scene, report);
    core::frameSceneOnContent(scene);
    core::saveScene(scene, out.file("final.3Dscene"));

    cfg.writeEffectiveConfig(out.file("config.ini"));
    cfg.writeOptionsInUse(out.file("options.ini"));
    describeRun(report, timer);
    const auto groundTruth = groundTruthName();
    std::optional<core::TEvalResult> evaluation;
    if (groundTruth) {
        report.setGroundTruth(*groundTruth);
        core::TEvalParams eval;
        eval.run_dir = out.path();
        eval.ground_truth = *groundTruth;
        evaluation = core::evaluateRunFolder(eval);
    }
    // last: a run.json that says completed stands for a whole folder
    report.setCompleted();
    report.write(out.file("run.json"));
    for (const auto& warning : report.warnings())  // on stderr, --quiet or not
        std::cerr << name << ": warning: " << warning << "\n";
    if (args.quiet) return;
    if (const auto& odometry = m_odometryTiming;
        odometry.interpolated + odometry.latest_reading > 0)
        std::cout << name << ": step odometry (per robot and step): " << odometry.at_step_time
                  << " read at the step's time, " << odometry.interpolated
                  << " interpolated to it, " << odometry.latest_reading
                  << " from the latest reading before it (doc/app-conventions.md)\n";
    std::cout << name << ": results in " << out.path() << " (final.3Dscene opens in SceneViewer3D)"
              << (evaluation ? "; against ground truth " + *groundTruth + " (metrics.json):\n"
                             : "; no ground truth, no metrics.json\n");
    if (evaluation) core::printEvalSummary(std::cout, *evaluation);
}

void SlamApp::describeRun(core::RunReport& report, const core::RunTimer& timer) const
{
    args.describeInputs(report, cfg.effectiveText(), rawlog, seed);
    report.setOpenCvVersion(CV_VERSION);
    report.setTiming(timer);
    const auto& odometry = m_odometryTiming;
    if (odometry.at_step_time + odometry.interpolated + odometry.latest_reading +
            odometry.frames_before_odometry >
        0) {
        report.setCount("odometry_at_step_time", static_cast<double>(odometry.at_step_time));
        report.setCount("odometry_interpolated", static_cast<double>(odometry.interpolated));
        report.setCount("odometry_latest_reading", static_cast<double>(odometry.latest_reading));
        report.setCount("frames_before_odometry",
                        static_cast<double>(odometry.frames_before_odometry));
    }
}

core::TumTrajectory SlamApp::asTrajectory(
    const std::vector<std::pair<double, mrpt::math::TPose2D>>& path)
{
    core::TumTrajectory t;
    for (const auto& [time, p] : path) {
        if (t.empty() || time > t.timestamps.back())
            t.push_back(time, mrpt::math::TPose3D(p));
        else if (time == t.timestamps.back())
            t.poses.back() = mrpt::math::TPose3D(p);
    }
    return t;
}

void SlamApp::drawOdometryAndGroundTruth(mrpt::opengl::COpenGLScene& scene,
                                         const core::TumTrajectory& odometry,
                                         const std::optional<core::TumTrajectory>& groundTruth,
                                         const std::string& robot)
{
    const std::string suffix = robot.empty() ? "" : " " + robot;
    scene.insert(core::trajectoryAsLines(odometry, {0.9f, 0.1f, 0.1f}, "odometry" + suffix));
    if (groundTruth)
        scene.insert(core::trajectoryAsLines(*groundTruth, {0, 0, 0}, "ground truth" + suffix));
}

const std::optional<core::LandmarkFile>& SlamApp::trueLandmarks(
    const std::string& groundTruthPrefix)
{
    if (!m_trueLandmarks || m_trueLandmarks->first != groundTruthPrefix) {
        const std::string file = groundTruthPrefix + ".landmarks.txt";
        std::optional<core::LandmarkFile> landmarks;
        if (mrpt::system::fileExists(file)) landmarks = core::LandmarkFile::loadTrueLandmarks(file);
        m_trueLandmarks.emplace(groundTruthPrefix, std::move(landmarks));
    }
    return m_trueLandmarks->second;
}

void SlamApp::drawLandmarks(mrpt::opengl::COpenGLScene& scene, const core::LandmarkFile& file)
{
    std::vector<mrpt::math::TPoint3D> points;
    for (const auto& lm : file.landmarks) points.push_back(lm.position);
    scene.insert(core::pointsAsCrosses(points, {0, 0, 0}));
}

}  // namespace mrpt_vslam::apps
