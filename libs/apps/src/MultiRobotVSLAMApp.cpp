#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/system/filesystem.h>
#include <mrpt_vslam/apps/MultiRobotVSLAMApp.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/EvalInputs.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/ObservationSelector.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/RunOutputs.h>
#include <mrpt_vslam/core/SingleRobotStart.h>
#include <mrpt_vslam/core/TextColumns.h>
#include <mrpt_vslam/multirobot/CMultiRobotVisualSLAM.h>
#include <mrpt_vslam/multirobot/LandmarkIdentityTally.h>
#include <mrpt_vslam/multirobot/StereoFrontEnd.h>
#include <mrpt_vslam/multirobot/TeamPathSmoother.h>
#include <mrpt_vslam/team/TeamListener.h>

#include <bitset>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "ParticleFilterApp.h"

namespace mrpt_vslam::apps {

using multirobot::CMultiRobotVisualSLAM;
using multirobot::CVisualLandmarksMap;
using multirobot::StereoFrontEnd;
using multirobot::TCorrespondence;
using multirobot::TeamPathSmoother;
using multirobot::TLandmarkIdentityTally;
using multirobot::TTeamParticle;
using multirobot::TVisualLandmark;

namespace {
constexpr const char* kAppSection = kMultiRobotVSLAMId.section;
constexpr const char* kFrontEndSection = "StereoFrontEnd";
constexpr const char* kSmootherSection = "TeamPathSmoother";
constexpr const char* kListenerSection = "TeamListener";
/// The keys of [TeamPathSmoother] that were in [MultiRobotVSLAM] before: (former, new).
constexpr std::pair<const char*, const char*> kMovedKeys[] = {
    {"map_along_path", "map_along_path"},
    {"map_along_path_D0", "D0"},
    {"map_along_path_min_times_seen", "min_seen_fraction"},
    {"smooth_paths", "smooth_paths"},
    {"smooth_paths_rounds", "rounds"},
    {"smooth_paths_huber", "huber"},
    {"smooth_paths_odometry_scale_std", "odometry_scale_std"},
    {"smooth_paths_motion_cov_factor", "motion_cov_factor"},
    {"smooth_paths_reanchor_gap", "reanchor_gap"},
    {"smooth_paths_reanchor_gain", "reanchor_gain"}};

/// Where the landmark measurements come from (ini key `input`).
enum class TInput { Auto, Landmarks, Stereo };

const std::vector<mrpt::img::TColorf> kRobotColours{{0.0f, 0.6f, 0.0f},
                                                    {0.0f, 0.3f, 0.9f},
                                                    {0.8f, 0.4f, 0.0f},
                                                    {0.6f, 0.0f, 0.6f},
                                                    {0.0f, 0.6f, 0.6f}};
mrpt::img::TColorf robotColour(size_t k) { return kRobotColours[k % kRobotColours.size()]; }
}  // namespace

struct MultiRobotVSLAMApp::Impl : ParticleFilterApp {
    Impl(MultiRobotVSLAMApp& owner, core::AppArguments arguments)
        : ParticleFilterApp(std::move(arguments), kMultiRobotVSLAMId.name, kAppSection), app(owner)
    {
    }

    MultiRobotVSLAMApp& app;  ///< where the results go
    std::string groundTruthPrefix;
    TInput input = TInput::Auto;
    bool startFromGroundTruth = true;
    /// One robot: the label of its CObservationOdometry readings ("": any).
    std::string odometryLabel;
    std::vector<mrpt::math::TPose2D> startPoses;
    double gtMatchRadius = 0.25;
    /// Independent filters run side by side; the one whose smoothed paths cost least is kept.
    size_t filterRuns = 1;

    CVisualLandmarksMap mapTemplate;
    CMultiRobotVisualSLAM::TOptions filterOptions;
    TeamPathSmoother::TOptions smootherOptions;
    StereoFrontEnd::TOptions frontEndOptions;
    team::TeamListener::TOptions listenerOptions;            ///< with --listen
    team::TeamListener* listener = nullptr;                  ///< with --listen, during run()
    std::vector<std::unique_ptr<StereoFrontEnd>> frontEnds;  ///< one per robot, on demand
    /// Its smoother records the run: the map along the path, the smoothing, the sensor pose
    /// checks.
    using Run = TFilterRun<CMultiRobotVisualSLAM, TeamPathSmoother>;
    /// filter_runs of them, from the seeds --seed, --seed + 1, ...; after endSteps() the kept one
    std::vector<Run> runs;
    /// The first run during the steps (its figures stand for all: they read the same data), the
    /// kept one after endSteps().
    CMultiRobotVisualSLAM& filter() const { return *runs.front().filter; }
    TeamPathSmoother& smoother() const { return *runs.front().smoother; }
    /// With smooth_paths, per run (by seed): what its smoothing gave.
    std::vector<TRunOutcome> runOutcomes;
    size_t keptRun = 0;  ///< of runOutcomes
    std::vector<std::optional<core::TumTrajectory>> groundTruth;
    std::vector<mrpt::poses::CPose2D> odometry;  ///< dead reckoning from the start poses

    size_t measurements = 0, stereoFrames = 0, landmarkObservations = 0;
    size_t robotReadings = 0, nonPositiveRanges = 0;
    StereoFrontEnd::TFrameStats frontEnd;  ///< of the stereo pairs through the front-end

    void findGroundTruth();
    /// One robot: the step's odometry alone (the best movement estimate of a rawlog's action
    /// collection).
    static mrpt::obs::CActionCollection::Ptr singleRobotAction(
        const mrpt::obs::CActionCollection& actions);
    /// Stereo images → landmarks where images are the input; counts the landmark inputs.
    void prepareFrame(mrpt::obs::CSensoryFrame& sf);
    /// Each sensor's pose on its robot as its first observation the filter reads gives it
    /// ("ROBOT SENSOR" → pose; SENSOR the label, or without one the class and, from the second
    /// unlabelled one of a frame on, its place): run.json.
    std::map<std::string, mrpt::poses::CPose3D> sensorPoses;
    /// Per robot, its sensors' names of sensorPoses in the order of TLandmarkMeasurement::sensor
    std::vector<std::vector<std::string>> sensorNames;
    void recordSensorPoses(const mrpt::obs::CSensoryFrame& sf);
    /// TeamPathSmoother::sensorPoseChecks() of `best` in run.json and the log, and a warning
    /// where a sensor's pose or the readings look wrong.
    void reportSensorPoseChecks(const TTeamParticle& best, core::RunReport& report,
                                bool quiet) const;
    /// With smooth_paths: the result of TeamPathSmoother::smoothPaths() and its time (all runs).
    std::optional<TeamPathSmoother::TSmoothedTeam> smoothed;
    double smoothingSeconds = 0;
    std::vector<core::TumTrajectory> filterPaths;  ///< the best particle's, when smoothed

    /// One robot's path of the best particle.
    core::TumTrajectory bestParticlePath(size_t robot) const;
    /// `paths` (one per robot) and `map`.
    void drawTeam(mrpt::opengl::COpenGLScene& scene, const CVisualLandmarksMap& map,
                  const std::vector<core::TumTrajectory>& paths) const;
    /** Where measurements carry identities (range-bearing data imported with kept ids): of the
     *  measurements fused into the landmarks of the output map, how many had another identity
     *  than the one that created the landmark, and how many identities have several landmarks;
     *  as JSON, empty without identities. */
    static std::string identityAssociationJson(const TLandmarkIdentityTally& tally);
    /// Merged vs duplicated landmarks of `map` against the true ones (doc/multirobot.md), as
    /// JSON.
    std::string landmarkMergingJson(const CVisualLandmarksMap& map,
                                    const core::LandmarkFile& truth) const;

    void loadConfig() override;
    void prepare() override;
    std::unique_ptr<core::RawlogEntrySource> openInput() override;
    std::vector<core::ObservationSelector> stepObservations() const override;
    std::vector<std::string> odometryLabels() const override;
    void step(mrpt::obs::CActionCollection::Ptr actions, mrpt::obs::CSensoryFrame& frame,
              core::RunTimer& timer) override;
    void drawLive(mrpt::opengl::COpenGLScene& scene) const override;
    void endSteps(const core::TRawlogSummary& contents) override;
    void writeResults(const core::OutputDirectory& out, mrpt::opengl::COpenGLScene& scene,
                      core::RunReport& report) override;
    std::optional<std::string> groundTruthName() const override;
};

MultiRobotVSLAMApp::MultiRobotVSLAMApp(core::AppArguments args)
    : outDir(args.outDir), m_impl(std::make_unique<Impl>(*this, std::move(args)))
{
}

MultiRobotVSLAMApp::~MultiRobotVSLAMApp() = default;

void MultiRobotVSLAMApp::initialize() { m_impl->initialize(); }

void MultiRobotVSLAMApp::run() { m_impl->run(); }

std::vector<core::TReadKey> MultiRobotVSLAMApp::configKeys() const { return m_impl->configKeys(); }

void MultiRobotVSLAMApp::Impl::loadConfig()
{
    input = readChoice<TInput>(
        "input",
        {{"auto", TInput::Auto}, {"landmarks", TInput::Landmarks}, {"stereo", TInput::Stereo}});
    startFromGroundTruth =
        cfg.read_bool(kAppSection, "start_poses_from_ground_truth", startFromGroundTruth);
    gtMatchRadius = cfg.read_double(kAppSection, "gt_match_radius", gtMatchRadius);
    odometryLabel = cfg.read_string(kAppSection, "odometry_label", "");
    if (!(gtMatchRadius > 0)) throw usageError("[MultiRobotVSLAM] gt_match_radius must be > 0");
    auto& l = listenerOptions;
    l.reorder_window_s = cfg.read_double(kListenerSection, "reorder_window_s", l.reorder_window_s);
    l.join_window_s = cfg.read_double(kListenerSection, "join_window_s", l.join_window_s);
    l.idle_timeout_s = cfg.read_double(kListenerSection, "idle_timeout_s", l.idle_timeout_s);
    for (const auto& [key, value] :
         {std::pair<const char*, double>{"reorder_window_s", l.reorder_window_s},
          {"join_window_s", l.join_window_s},
          {"idle_timeout_s", l.idle_timeout_s}})
        if (!(value > 0 && value <= 86400))
            throw usageError(std::string("[") + kListenerSection + "] " + key +
                             " must be > 0 and at most 86400 [s]");
    l.quiet = args.quiet;

    try {
        filterOptions.loadFromConfigFile(cfg, kAppSection);
        smootherOptions.loadFromConfigFile(cfg, kSmootherSection);
        frontEndOptions.loadFromConfigFile(cfg, kFrontEndSection);
        mapTemplate = particleMapTemplate<CVisualLandmarksMap>("visualLandmarksMap_count");
    } catch (const core::UsageError&) {
        throw;
    } catch (const std::exception& e) {
        throw configError(e);
    }
    // the class's two robots are no guess for a user's rawlog
    if (!cfg.keyExists(kAppSection, "robots"))
        throw usageError(
            "[MultiRobotVSLAM] robots is missing: the robots' names, one for a "
            "single-robot rawlog (robots = R1)");
    for (const auto& robot : filterOptions.robots) {
        const std::string key = "start_pose_" + robot;
        std::vector<double> v;
        try {
            v = core::readNumberList(cfg, kAppSection, key, {});
        } catch (const core::UsageError& e) {
            throw usageError(e.what());
        }
        if (v.empty() && robot == filterOptions.robots.front()) v = {0, 0, 0};
        if (v.empty() && !startFromGroundTruth)
            throw usageError("[MultiRobotVSLAM] " + key + " = x y yaw_deg is missing");
        if (!v.empty() && v.size() != 3)
            throw usageError("[MultiRobotVSLAM] " + key + " must be 'x y yaw_deg'");
        startPoses.push_back(v.empty() ? mrpt::math::TPose2D()
                                       : mrpt::math::TPose2D(v[0], v[1], mrpt::DEG2RAD(v[2])));
    }
    filterRuns = loadFilterRuns(filterRuns, smootherOptions.smooth_paths,
                                "[" + std::string(kSmootherSection) + "] smooth_paths");
    loadParticleFilterOptions();
    if (!odometryLabel.empty() && filterOptions.robots.size() != 1)
        throw usageError(
            "[MultiRobotVSLAM] odometry_label is for one robot; a team's odometry is "
            "labelled <ROBOT>_ODOM");
    for (const auto& [former, key] : kMovedKeys)
        if (cfg.keyExists(kAppSection, former))
            throw usageError(std::string("[MultiRobotVSLAM] ") + former + ": moved to [" +
                             kSmootherSection + "] " + key);
}

void MultiRobotVSLAMApp::Impl::findGroundTruth()
{
    groundTruthPrefix = args.groundTruthPrefix(rawlog);
    size_t found = 0;
    for (size_t k = 0; k < filterOptions.robots.size(); k++) {
        const std::string tum = core::groundTruthFileOf(groundTruthPrefix, filterOptions.robots[k],
                                                        filterOptions.robots.size() == 1);
        groundTruth.emplace_back();
        if (!mrpt::system::fileExists(tum)) continue;
        groundTruth.back() = core::TumTrajectory::loadGroundTruth(tum);
        found++;
    }
    if (found == 0 && !args.groundTruth.empty()) {
        std::string looked;
        for (const auto& robot : filterOptions.robots)
            looked += (looked.empty() ? "" : ", ") +
                      core::groundTruthFileOf(groundTruthPrefix, robot, false);
        if (filterOptions.robots.size() == 1)
            looked += " or " + core::groundTruthFileOf(groundTruthPrefix, "", false);
        throw std::runtime_error("--ground-truth " + args.groundTruth +
                                 ": no such file: " + looked);
    }
    if (startFromGroundTruth && found < filterOptions.robots.size())
        for (size_t k = 1; k < filterOptions.robots.size(); k++)
            if (!groundTruth[k] &&
                !cfg.keyExists(kAppSection, "start_pose_" + filterOptions.robots[k]))
                throw usageError("[MultiRobotVSLAM] no ground truth for " +
                                 filterOptions.robots[k] + ": give start_pose_" +
                                 filterOptions.robots[k] + " = x y yaw_deg");
}

void MultiRobotVSLAMApp::Impl::recordSensorPoses(const mrpt::obs::CSensoryFrame& sf)
{
    using core::ObservationSelector;
    const auto& o = filterOptions;
    sensorNames.resize(o.robots.size());
    for (size_t k = 0; k < o.robots.size(); k++) {
        size_t unlabelled = 0;  // told apart by their order in the frame
        const bool named = !sensorNames[k].empty();
        const auto record = [&](const mrpt::obs::CObservation& obs,
                                const mrpt::poses::CPose3D& pose) {
            std::string sensor = o.robots[k] + " " + ObservationSelector::nameOf(obs);
            if (obs.sensorLabel.empty() && unlabelled++ > 0)
                sensor += " " + std::to_string(unlabelled);
            sensorPoses.try_emplace(sensor, pose);
            if (!named) sensorNames[k].push_back(sensor);
        };
        for (const auto& obs : ObservationSelector::allIn<mrpt::obs::CObservationVisualLandmarks>(
                 sf, o.inputLabel(k, o.landmarks_suffix)))
            record(*obs, obs->refCameraPose);
        for (const auto& obs : ObservationSelector::allIn<mrpt::obs::CObservationBearingRange>(
                 sf, o.inputLabel(k, o.range_bearing_suffix)))
            record(*obs, obs->sensorLocationOnRobot);
    }
}

void MultiRobotVSLAMApp::Impl::prepareFrame(mrpt::obs::CSensoryFrame& sf)
{
    using core::ObservationSelector;
    const auto& o = filterOptions;
    if (frontEnds.empty()) frontEnds.resize(o.robots.size());
    for (size_t k = 0; k < o.robots.size(); k++) {
        const std::string landmarksLabel = o.inputLabel(k, o.landmarks_suffix);
        const auto stereo = ObservationSelector::firstIn<mrpt::obs::CObservationStereoImages>(
            sf, o.inputLabel(k, "_STEREO"));
        const bool hasLandmarks =
            ObservationSelector::firstIn<mrpt::obs::CObservationVisualLandmarks>(sf,
                                                                                 landmarksLabel) ||
            ObservationSelector::firstIn<mrpt::obs::CObservationBearingRange>(
                sf, o.inputLabel(k, o.range_bearing_suffix));
        if (stereo) stereoFrames++;
        if (input == TInput::Landmarks || (input == TInput::Auto && hasLandmarks) || !stereo) {
            landmarkObservations += hasLandmarks ? 1 : 0;
            continue;
        }
        if (!frontEnds[k]) frontEnds[k] = std::make_unique<StereoFrontEnd>(frontEndOptions);
        mrpt::obs::CObservationVisualLandmarks::Ptr landmarks;
        try {
            landmarks = frontEnds[k]->process(*stereo);
        } catch (const std::exception& e) {
            const std::string images = core::RawlogReader::describeExternalImages(*stereo, rawlog);
            throw std::runtime_error(rawlog + ": step " + std::to_string(steps) + ": cannot use " +
                                     core::ObservationSelector::nameOf(*stereo) +
                                     (images.empty() ? "" : " (" + images + ")") + ": " +
                                     core::oneLineMessage(e));
        }
        // the images' landmarks replace any the frame had
        ObservationSelector::of<mrpt::obs::CObservationVisualLandmarks>(landmarksLabel)
            .eraseFrom(sf);
        const auto& stats = frontEnds[k]->lastFrameStats();
        frontEnd += stats;
        landmarks->sensorLabel = landmarksLabel.empty() ? stereo->sensorLabel : landmarksLabel;
        sf.insert(landmarks);
        stereo->imageLeft.unload();
        stereo->imageRight.unload();
        landmarkObservations++;
    }
}

mrpt::obs::CActionCollection::Ptr MultiRobotVSLAMApp::Impl::singleRobotAction(
    const mrpt::obs::CActionCollection& actions)
{
    const auto move = actions.getBestMovementEstimation();
    auto one = mrpt::obs::CActionCollection::Create();
    if (!move) return one;  // the filter names what is missing
    one->insert(*move);
    return one;
}

void MultiRobotVSLAMApp::Impl::prepare()
{
    findGroundTruth();
    app.robots = filterOptions.robots;
    for (size_t run = 0; run < filterRuns; run++) {
        Run r{makeFilter<CMultiRobotVisualSLAM>(mapTemplate, static_cast<uint32_t>(run)), nullptr};
        r.filter->options = filterOptions;
        r.smoother = std::make_unique<TeamPathSmoother>(mapTemplate);
        r.smoother->options = smootherOptions;
        r.filter->setStepObserver(r.smoother.get());
        runs.push_back(std::move(r));
    }
    for (const auto& p : startPoses) odometry.emplace_back(p);
    app.estimatedPaths.assign(app.robots.size(), {});
    app.odometryPaths.assign(app.robots.size(), {});
}

std::unique_ptr<core::RawlogEntrySource> MultiRobotVSLAMApp::Impl::openInput()
{
    if (args.listen.empty()) return SlamApp::openInput();
    auto live = std::make_unique<team::TeamListener>(args.listen, app.robots, listenerOptions);
    listener = live.get();
    if (!args.quiet)
        std::printf("multirobot-vslam: listening at %s for %zu robots\n", args.listen.c_str(),
                    app.robots.size());
    return live;
}

std::vector<core::ObservationSelector> MultiRobotVSLAMApp::Impl::stepObservations() const
{
    using core::ObservationSelector;
    const auto& o = filterOptions;
    std::vector<ObservationSelector> selectors;
    for (size_t k = 0; k < o.robots.size(); k++) {
        selectors.push_back(ObservationSelector::of<mrpt::obs::CObservationVisualLandmarks>(
            o.inputLabel(k, o.landmarks_suffix)));
        selectors.push_back(ObservationSelector::of<mrpt::obs::CObservationBearingRange>(
            o.inputLabel(k, o.range_bearing_suffix)));
        if (!o.robot_reading_ids.empty() && o.robots.size() > 1)
            selectors.push_back(ObservationSelector::of<mrpt::obs::CObservationBearingRange>(
                o.robots[k] + o.robot_readings_suffix));
        // one stereo pair per robot (its calibration); landmark readings of several sensors
        // are all read
        selectors.push_back(ObservationSelector::ofOneSensor<mrpt::obs::CObservationStereoImages>(
            o.inputLabel(k, "_STEREO"), ownKey("sensor_label")));
    }
    return selectors;
}

std::vector<std::string> MultiRobotVSLAMApp::Impl::odometryLabels() const
{
    const auto& robots = filterOptions.robots;
    if (robots.size() == 1)
        return odometryLabel.empty() ? std::vector<std::string>{}
                                     : std::vector<std::string>{odometryLabel};
    std::vector<std::string> labels;
    for (const auto& robot : robots) labels.push_back(robot + "_ODOM");
    return labels;
}

core::TumTrajectory MultiRobotVSLAMApp::Impl::bestParticlePath(size_t robot) const
{
    return asTrajectory(CMultiRobotVisualSLAM::pathOf(filter().bestParticle(), robot));
}

void MultiRobotVSLAMApp::Impl::drawTeam(mrpt::opengl::COpenGLScene& scene,
                                        const CVisualLandmarksMap& map,
                                        const std::vector<core::TumTrajectory>& paths) const
{
    scene.insert(mrpt::opengl::CGridPlaneXY::Create(-15, 15, -10, 10, 0, 1));
    scene.insert(map.getVisualization());
    for (size_t k = 0; k < paths.size(); k++)
        scene.insert(core::trajectoryAsLines(paths[k], robotColour(k),
                                             "estimate " + filterOptions.robots[k]));
}

void MultiRobotVSLAMApp::Impl::step(mrpt::obs::CActionCollection::Ptr actions,
                                    mrpt::obs::CSensoryFrame& frame, core::RunTimer& timer)
{
    const auto& robots = app.robots;
    if (robots.size() == 1) actions = singleRobotAction(*actions);
    prepareFrame(frame);
    recordSensorPoses(frame);
    const double t = stepTime(actions->begin()->get()->timestamp);
    if (steps == 0) {
        for (size_t k = 0; k < robots.size(); k++)
            if (startFromGroundTruth && groundTruth[k]) {
                const auto move =
                    std::dynamic_pointer_cast<mrpt::obs::CActionRobotMovement2D>(actions->get(k));
                // (no movement: the filter's step says so)
                const auto u =
                    move ? move->poseChange->getMeanVal().asTPose() : mrpt::math::TPose2D();
                startPoses[k] = core::groundTruthPoseAtStart(
                    *groundTruth[k], t, u,
                    core::groundTruthFileOf(groundTruthPrefix, robots[k], robots.size() == 1),
                    "[MultiRobotVSLAM] start_poses_from_ground_truth");
                odometry[k] = mrpt::poses::CPose2D(startPoses[k]);
            }
        for (auto& run : runs) run.filter->reset(startPoses, t);
    }
    filterStep(*actions, frame, timer);

    for (size_t k = 0; k < robots.size(); k++) {
        const auto move =
            std::dynamic_pointer_cast<mrpt::obs::CActionRobotMovement2D>(actions->get(k));
        odometry[k] = odometry[k] + move->poseChange->getMeanVal();
        app.odometryPaths[k].push_back(t, mrpt::math::TPose3D(odometry[k].asTPose()));
    }
    measurements += filter().lastStepStats.measurements;
    robotReadings += filter().lastStepStats.robot_readings;
    nonPositiveRanges += filter().lastStepStats.non_positive_ranges;
}

void MultiRobotVSLAMApp::Impl::drawLive(mrpt::opengl::COpenGLScene& scene) const
{
    std::vector<core::TumTrajectory> paths;
    for (size_t k = 0; k < app.robots.size(); k++) paths.push_back(bestParticlePath(k));
    drawTeam(scene, filter().bestParticle().map, paths);
}

void MultiRobotVSLAMApp::Impl::endSteps(const core::TRawlogSummary& contents)
{
    const auto& robots = app.robots;
    const auto& o = filterOptions;
    std::string odoLabels;
    for (const auto& l : odometryLabels()) odoLabels += (odoLabels.empty() ? "" : ", ") + l;
    const std::string inputs =
        robots.size() == 1
            ? "odometry (CActionRobotMovement2D, or CObservationOdometry" +
                  core::ObservationSelector::labelled(odoLabels) +
                  ") and CObservationBearingRange, CObservationVisualLandmarks or "
                  "CObservationStereoImages" +
                  core::ObservationSelector::labelled(o.sensor_label)
            : "observation-only rawlog with " + odoLabels + " and <ROBOT>" + o.landmarks_suffix +
                  ", <ROBOT>" + o.range_bearing_suffix + " or <ROBOT>_STEREO";
    if (steps == 0 && listener) {
        size_t connections = 0;
        for (const auto& s : listener->stats()) connections += s.connections;
        if (connections == 0)
            throw std::runtime_error(
                args.listen + ": no robot node connected within [TeamListener] idle_timeout_s = " +
                mrpt::format("%g", listenerOptions.idle_timeout_s) +
                " s (one vslam-robot-node --connect per robot, doc/team-online.md)");
    }
    if (steps == 0)
        throw std::runtime_error(rawlog + ": no steps (" + inputs +
                                 "); the rawlog has: " + contents.describe());
    if (measurements == 0 && frontEnd.frames > 0 && frontEnd.emitted == 0)
        throw std::runtime_error(rawlog +
                                 ": no landmark measurements: the stereo front-end found "
                                 "none in " +
                                 std::to_string(frontEnd.frames) + " stereo pairs: " +
                                 StereoFrontEnd::whyNoLandmarks(frontEnd, frontEndOptions));
    if (measurements == 0)
        throw std::runtime_error(rawlog + ": no landmark measurements (" + inputs +
                                 "); the rawlog has: " + contents.describe());
    if (smootherOptions.smooth_paths) {
        const core::RunTimer smoothing;
        auto results = keepCheapestRun(
            runs, [](const Run& r) { return r.smoother->smoothPaths(r.filter->bestParticle()); },
            [](const TeamPathSmoother::TSmoothedTeam& s) { return s.cost; }, keptRun);
        for (const auto& s : results)
            runOutcomes.push_back({s.cost, s.map.size(), s.correspondences.size()});
        smoothed = std::move(results[keptRun]);
        smoothingSeconds = smoothing.elapsedSeconds();
    }
    for (size_t k = 0; k < robots.size(); k++) app.estimatedPaths[k] = bestParticlePath(k);
    if (smoothed) {
        filterPaths = app.estimatedPaths;
        for (size_t k = 0; k < robots.size(); k++)
            app.estimatedPaths[k] = asTrajectory(smoothed->paths[k]);
    }
}

std::string MultiRobotVSLAMApp::Impl::landmarkMergingJson(const CVisualLandmarksMap& map,
                                                          const core::LandmarkFile& truth) const
{
    // each map landmark goes to its nearest true landmark within gt_match_radius
    std::vector<size_t> count(truth.landmarks.size(), 0);
    std::vector<uint32_t> robotsOf(truth.landmarks.size(), 0), bitsOfOne(truth.landmarks.size(), 0);
    size_t unmatched = 0, severalRobots = 0;
    map.landmarks().forEach([&](uint32_t, const TVisualLandmark& lm) {
        if (std::bitset<32>(lm.seen_by).count() > 1) severalRobots++;
        double bestD = gtMatchRadius;
        std::optional<size_t> g;
        for (size_t i = 0; i < truth.landmarks.size(); i++) {
            const auto& p = truth.landmarks[i].position;
            const double dist = (lm.mean - Eigen::Vector3d(p.x, p.y, p.z)).norm();
            if (dist <= bestD) bestD = dist, g = i;
        }
        if (!g) {
            unmatched++;
            return;
        }
        count[*g]++;
        robotsOf[*g] |= lm.seen_by;
        bitsOfOne[*g] = lm.seen_by;
    });
    size_t mapped = 0, once = 0, duplicated = 0, byTeam = 0, byTeamMerged = 0, byTeamDuplicated = 0;
    for (size_t i = 0; i < count.size(); i++) {
        if (count[i] == 0) continue;
        mapped++;
        (count[i] == 1 ? once : duplicated)++;
        if (std::bitset<32>(robotsOf[i]).count() < 2) continue;
        byTeam++;  // measured by several robots, through one landmark or several
        if (count[i] == 1 && std::bitset<32>(bitsOfOne[i]).count() >= 2)
            byTeamMerged++;
        else
            byTeamDuplicated++;
    }
    std::ostringstream j;
    j << "{\"match_radius_m\": " << gtMatchRadius << ", \"map_landmarks\": " << map.size()
      << ", \"map_landmarks_seen_by_several_robots\": " << severalRobots
      << ", \"map_landmarks_without_true_landmark\": " << unmatched
      << ", \"true_landmarks\": " << truth.landmarks.size()
      << ", \"true_landmarks_mapped\": " << mapped << ", \"true_landmarks_mapped_once\": " << once
      << ", \"true_landmarks_duplicated\": " << duplicated
      << ", \"true_landmarks_seen_by_several_robots\": " << byTeam
      << ", \"of_those_merged\": " << byTeamMerged
      << ", \"of_those_duplicated\": " << byTeamDuplicated << "}";
    return j.str();
}

std::string MultiRobotVSLAMApp::Impl::identityAssociationJson(const TLandmarkIdentityTally& tally)
{
    if (tally.landmarks_with_identity == 0) return "";
    std::ostringstream j;
    j << "{\"landmarks_with_identity\": " << tally.landmarks_with_identity
      << ", \"identities\": " << tally.identities
      << ", \"identities_with_several_landmarks\": " << tally.identities_with_several_landmarks
      << ", \"fused_measurements\": " << tally.fused_measurements
      << ", \"fused_with_another_identity\": " << tally.fused_with_another_identity << "}";
    return j.str();
}

void MultiRobotVSLAMApp::Impl::writeResults(const core::OutputDirectory& out,
                                            mrpt::opengl::COpenGLScene& scene,
                                            core::RunReport& report)
{
    const auto& best = filter().bestParticle();
    for (size_t k = 0; k < app.robots.size(); k++) {
        const std::string& r = app.robots[k];
        app.estimatedPaths[k].save(
            out.file("estimated_path_" + r + ".tum"),
            "multirobot-vslam: " + std::string(smoothed ? "smoothed" : "best particle's") +
                " path of " + r);
        app.odometryPaths[k].save(out.file("odometry_path_" + r + ".tum"),
                                  "multirobot-vslam: dead reckoning of " + r);
        if (smoothed)
            filterPaths[k].save(
                out.file("filter_path_" + r + ".tum"),
                "multirobot-vslam: best particle's path of " + r + ", before smoothing");
    }
    // the output map: the best particle's own, or the one made along its final path, or
    // along the smoothed paths
    std::optional<CVisualLandmarksMap> alongPath;
    std::vector<TCorrespondence> alongPathCorrespondences;
    double alongPathSeconds = 0;
    if (smootherOptions.map_along_path && !smoothed) {
        const core::RunTimer rebuild;
        alongPath = smoother().mapAlongPath(best, &alongPathCorrespondences);
        alongPathSeconds = rebuild.elapsedSeconds();
    }
    if (smootherOptions.map_along_path) core::saveMapFiles(best.map, out.path(), "particle_map");
    const CVisualLandmarksMap& map = smoothed ? smoothed->map : alongPath ? *alongPath : best.map;
    // the correspondences `map` was made with
    const std::vector<TCorrespondence> correspondences =
        smoothed    ? smoothed->correspondences
        : alongPath ? alongPathCorrespondences
                    : TLandmarkIdentityTally::historyOf(best);
    core::saveFinalMap(map, out.path());

    drawTeam(scene, map, app.estimatedPaths);
    for (size_t k = 0; k < app.robots.size(); k++)
        drawOdometryAndGroundTruth(scene, app.odometryPaths[k], groundTruth[k], app.robots[k]);
    const auto& landmarks = trueLandmarks(groundTruthPrefix);
    if (landmarks) drawLandmarks(scene, *landmarks);

    report.setCount("robots", static_cast<double>(app.robots.size()));
    report.setCount("steps", static_cast<double>(steps));
    report.setCount("stereo_frames", static_cast<double>(stereoFrames));
    report.setCount("stereo_frames_rectified", static_cast<double>(frontEnd.rectified));
    if (frontEnd.rectified > 0 && !args.quiet)
        std::printf(
            "multirobot-vslam: %zu stereo pairs rectified from their calibration (%s); "
            "the camera pose is the rectified left camera's\n",
            frontEnd.rectified, frontEnd.rectified_because.c_str());
    report.setCount("landmark_observations", static_cast<double>(landmarkObservations));
    report.setCount("measurements", static_cast<double>(measurements));
    report.setCount("robot_readings", static_cast<double>(robotReadings));
    report.setCount("readings_with_non_positive_range", static_cast<double>(nonPositiveRanges));
    if (nonPositiveRanges > 0 && !args.quiet)
        std::printf("multirobot-vslam: %zu range-bearing readings with a range <= 0 left out\n",
                    nonPositiveRanges);
    report.setCount("particles", static_cast<double>(filter().particlesCount()));
    report.setCount("landmarks", static_cast<double>(map.size()));
    // the sensors' poses on the robots: always the observations' own (no config key sets them)
    std::string poses;
    for (const auto& [sensor, pose] : sensorPoses) {
        poses += (poses.empty() ? "\"" : ", \"") + sensor + "\": " + poseJsonArray(pose);
        if (!args.quiet)
            std::printf("multirobot-vslam: %s on the robot from the observations: %s\n",
                        sensor.c_str(), poseText(pose).c_str());
    }
    report.setResultJson("sensor_poses_on_robot",
                         "{\"source\": \"observations\", "
                         "\"x_y_z_m_yaw_pitch_roll_deg\": {" +
                             poses + "}}");
    reportSensorPoseChecks(best, report, args.quiet);
    // The shipped data start a landmark per 5 (office team) to 120 (MRCLAM) measurements; one
    // per two: the measurements are rarely associated again, the paths are the odometry's.
    if (measurements > 0 && 2 * best.map.size() >= measurements)
        report.addWarning(mrpt::format(
            "the best particle started a landmark for %zu of the %zu measurements: few were "
            "associated again, so they hardly corrected the odometry; check the measurement "
            "noise, the sensor pose on the robot and search_radius (doc/multirobot.md)",
            best.map.size(), measurements));
    if (smootherOptions.map_along_path) {
        report.setCount("particle_map_landmarks", static_cast<double>(best.map.size()));
        report.setCount("map_along_path_min_times_seen",
                        static_cast<double>(smoother().minTimesSeen()));
    }
    if (alongPath) report.setResult("map_along_path_s", alongPathSeconds);
    if (smoothed) {
        report.setResult("smoothing_s", smoothingSeconds);
        report.setCount("smoothing_iterations", static_cast<double>(smoothed->iterations));
        report.setResult("smoothing_cost", smoothed->cost);
        reportFilterRuns(runOutcomes, keptRun, report);
        report.setCount("smoothing_readings", static_cast<double>(smoothed->readings));
        report.setCount("smoothing_outlier_readings",
                        static_cast<double>(smoothed->outlier_readings));
        // With the noise right, a planar reading lies beyond h σ with probability exp(−h²/2)
        // (1 in 90 at h = 3); the stock simul-landmarks rawlogs and MRCLAM stay below 1 in 40,
        // a wrong sensor pose or a noise ten times too small puts a quarter to half beyond.
        if (10 * smoothed->outlier_readings > smoothed->readings)
            report.addWarning(mrpt::format(
                "after smoothing, %zu of the %zu readings lie beyond %g sigma of their landmarks "
                "(about 1 in %.0f would with the noise right): readings and odometry disagree; "
                "check the measurement noise and the sensor pose on the robot (doc/multirobot.md)",
                smoothed->outlier_readings, smoothed->readings, smootherOptions.huber,
                std::exp(smootherOptions.huber * smootherOptions.huber / 2)));
        report.setCount("smoothing_reanchored", static_cast<double>(smoothed->reanchored));
        if (!smoothed->odometry_scales.empty()) {
            std::ostringstream j;
            for (size_t k = 0; k < app.robots.size(); k++)
                j << (k ? ", " : "{") << "\"" << app.robots[k] << "\": ["
                  << smoothed->odometry_scales[k][0] << ", " << smoothed->odometry_scales[k][1]
                  << "]";
            report.setResultJson("smoothing_odometry_scales", j.str() + "}");
        }
    }
    if (landmarks) report.setResultJson("landmark_merging", landmarkMergingJson(map, *landmarks));
    if (listener) report.setResultJson("team_link", listener->statsJson());
    if (const auto a = identityAssociationJson(TLandmarkIdentityTally::of(correspondences, map));
        !a.empty())
        report.setResultJson("association_by_identity", a);
}

void MultiRobotVSLAMApp::Impl::reportSensorPoseChecks(const TTeamParticle& best,
                                                      core::RunReport& report, bool quiet) const
{
    const core::RunTimer timer;
    const auto nameOf = [&](size_t robot, uint16_t sensor) {
        const bool known = robot < sensorNames.size() && sensor < sensorNames[robot].size();
        return known ? sensorNames[robot][sensor]
                     : app.robots[robot] + " sensor " + std::to_string(sensor + 1);
    };
    std::vector<TSensorCheck> named;
    for (auto& c : smoother().sensorPoseChecks(best)) {
        named.push_back({nameOf(c.robot, c.sensor), c.correction, c.tilt, {}});
        for (const auto& h : c.heights)
            named.back().heights.emplace_back(nameOf(h.robot, h.sensor), h.offset);
    }
    apps::reportSensorPoseChecks("multirobot-vslam", "a landmark", "doc/multirobot.md", named,
                                 timer.elapsedSeconds(), report, quiet);
}

std::optional<std::string> MultiRobotVSLAMApp::Impl::groundTruthName() const
{
    for (const auto& g : groundTruth)
        if (g) return groundTruthPrefix;
    return std::nullopt;
}

}  // namespace mrpt_vslam::apps
