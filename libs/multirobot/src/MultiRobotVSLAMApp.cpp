#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt/system/filesystem.h>
#include <mrpt_vslam/core/ActionFrameSource.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/EvalInputs.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/LiveView.h>
#include <mrpt_vslam/core/ObservationSelector.h>
#include <mrpt_vslam/core/OutputDirectory.h>
#include <mrpt_vslam/core/ProgressReporter.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/RunEvaluation.h>
#include <mrpt_vslam/core/RunOutputs.h>
#include <mrpt_vslam/core/RunReport.h>
#include <mrpt_vslam/core/RunTimer.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/multirobot/CMultiRobotVisualSLAM.h>
#include <mrpt_vslam/multirobot/LandmarkIdentityTally.h>
#include <mrpt_vslam/multirobot/MultiRobotVSLAMApp.h>
#include <mrpt_vslam/multirobot/StereoFrontEnd.h>
#include <mrpt_vslam/multirobot/TeamPathSmoother.h>

#include <bitset>
#include <cstdio>
#include <opencv2/core/version.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace mrpt_vslam::multirobot {

namespace {
constexpr const char* kAppSection = "MultiRobotVSLAM";
constexpr const char* kMapSection = "MappingApplication";
constexpr const char* kFrontEndSection = "StereoFrontEnd";
constexpr const char* kSmootherSection = "TeamPathSmoother";
/// The keys of [TeamPathSmoother] that were in [MultiRobotVSLAM] before: (former, new).
constexpr std::pair<const char*, const char*> kMovedKeys[] = {
    {"map_along_path", "map_along_path"},
    {"map_along_path_D0", "D0"},
    {"map_along_path_min_times_seen", "min_times_seen"},
    {"smooth_paths", "smooth_paths"},
    {"smooth_paths_rounds", "rounds"},
    {"smooth_paths_huber", "huber"},
    {"smooth_paths_odometry_scale_std", "odometry_scale_std"},
    {"smooth_paths_motion_cov_factor", "motion_cov_factor"},
    {"smooth_paths_reanchor_gap", "reanchor_gap"},
    {"smooth_paths_reanchor_gain", "reanchor_gain"}};

/// Where the landmark measurements come from (ini key `input`).
enum class TInput { Auto, Landmarks, Stereo };

mrpt::math::TPose3D to3D(const mrpt::math::TPose2D& p) { return {p.x, p.y, 0, p.phi, 0, 0}; }

const std::vector<mrpt::img::TColorf> kRobotColours{{0.0f, 0.6f, 0.0f},
                                                    {0.0f, 0.3f, 0.9f},
                                                    {0.8f, 0.4f, 0.0f},
                                                    {0.6f, 0.0f, 0.6f},
                                                    {0.0f, 0.6f, 0.6f}};
mrpt::img::TColorf robotColour(size_t k) { return kRobotColours[k % kRobotColours.size()]; }
}  // namespace

struct MultiRobotVSLAMApp::Impl {
    core::AppArguments args;
    core::CheckedConfigFile cfg;
    std::string rawlog, groundTruthPrefix;
    uint32_t seed = 1;
    TInput input = TInput::Auto;
    bool startFromGroundTruth = true;
    /// One robot: the label of its CObservationOdometry readings ("": any).
    std::string odometryLabel;
    std::vector<mrpt::math::TPose2D> startPoses;
    double gtMatchRadius = 0.25;

    mrpt::bayes::CParticleFilter pf;
    CVisualLandmarksMap mapTemplate;
    CMultiRobotVisualSLAM::TOptions filterOptions;
    TeamPathSmoother::TOptions smootherOptions;
    StereoFrontEnd::TOptions frontEndOptions;
    std::vector<std::unique_ptr<StereoFrontEnd>> frontEnds;  ///< one per robot, on demand
    std::unique_ptr<CMultiRobotVisualSLAM> filter;
    std::unique_ptr<TeamPathSmoother> smoother;  ///< with map_along_path
    std::vector<std::optional<core::TumTrajectory>> groundTruth;
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions motionModel;
    std::unique_ptr<core::LiveView> window;  ///< --gui

    size_t steps = 0, measurements = 0, stereoFrames = 0, landmarkObservations = 0;
    size_t robotReadings = 0, nonPositiveRanges = 0;

    void loadConfig();
    void findGroundTruth();
    /** One robot: the step's odometry alone (the best movement estimate of a rawlog's action
     *  collection), stamped with the frame's time when the rawlog's action has none. */
    static mrpt::obs::CActionCollection::Ptr singleRobotAction(
        const mrpt::obs::CActionCollection& actions, const mrpt::obs::CSensoryFrame& frame);
    /// Stereo images → landmarks where images are the input; counts the landmark inputs.
    void prepareFrame(mrpt::obs::CSensoryFrame& sf);
    /// With smooth_paths: the result of TeamPathSmoother::smoothPaths() and its time.
    std::optional<TeamPathSmoother::TSmoothedTeam> smoothed;
    double smoothingSeconds = 0;
    std::vector<core::TumTrajectory> filterPaths;  ///< the best particle's, when smoothed

    /// One robot's path of the best particle.
    core::TumTrajectory bestParticlePath(size_t robot) const;
    /// `paths` (one per robot) and `map`.
    void drawTeam(mrpt::opengl::COpenGLScene& scene, const CVisualLandmarksMap& map,
                  const std::vector<core::TumTrajectory>& paths) const;
    void writeOutputs(MultiRobotVSLAMApp& app, const core::RunTimer& timer);
    /** Where measurements carry identities (range-bearing data imported with kept ids): of the
     *  measurements fused into the landmarks of the output map, how many had another identity
     *  than the one that created the landmark, and how many identities have several landmarks;
     *  as JSON, empty without identities. */
    static std::string identityAssociationJson(const TLandmarkIdentityTally& tally);
    /// Merged vs duplicated landmarks of `map` against the true ones (doc/multirobot.md), as
    /// JSON.
    std::string landmarkMergingJson(const CVisualLandmarksMap& map,
                                    const core::LandmarkFile& truth) const;
};

MultiRobotVSLAMApp::MultiRobotVSLAMApp(core::AppArguments args) : m_impl(std::make_unique<Impl>())
{
    m_impl->args = std::move(args);
}

MultiRobotVSLAMApp::~MultiRobotVSLAMApp() = default;

void MultiRobotVSLAMApp::Impl::loadConfig()
{
    cfg.loadFile(args.configFile, args.overrides);
    const std::string& name = cfg.name();
    const auto usage = [&](const std::string& what) {
        return core::UsageError(name + ": " + what);
    };

    rawlog = args.resolveRawlog(cfg, kAppSection);
    seed = args.resolveSeed(static_cast<uint32_t>(cfg.read_int(kAppSection, "random_seed", 0)));
    const std::string in = cfg.read_string(kAppSection, "input", "auto");
    if (in == "auto")
        input = TInput::Auto;
    else if (in == "landmarks")
        input = TInput::Landmarks;
    else if (in == "stereo")
        input = TInput::Stereo;
    else
        throw usage("[MultiRobotVSLAM] input must be auto, landmarks or stereo, not '" + in + "'");
    startFromGroundTruth =
        cfg.read_bool(kAppSection, "start_poses_from_ground_truth", startFromGroundTruth);
    gtMatchRadius = cfg.read_double(kAppSection, "gt_match_radius", gtMatchRadius);
    odometryLabel = cfg.read_string(kAppSection, "odometry_label", "");
    if (!(gtMatchRadius > 0)) throw usage("[MultiRobotVSLAM] gt_match_radius must be > 0");

    try {
        filterOptions.loadFromConfigFile(cfg, kAppSection);
        smootherOptions.loadFromConfigFile(cfg, kSmootherSection);
        pf.m_options.loadFromConfigFile(cfg, "ParticleFilter");
        frontEndOptions.loadFromConfigFile(cfg, kFrontEndSection);
        motionModel = core::ActionFrameSource::loadMotionModel(cfg, "MotionModel");
    } catch (const std::exception& e) {
        throw usage(core::oneLineMessage(e));
    }
    for (const auto& robot : filterOptions.robots) {
        const std::string key = "start_pose_" + robot;
        std::vector<double> v;
        cfg.read_vector(kAppSection, key, std::vector<double>(), v);
        if (v.empty() && robot == filterOptions.robots.front()) v = {0, 0, 0};
        if (v.empty() && !startFromGroundTruth)
            throw usage("[MultiRobotVSLAM] " + key + " = x y yaw_deg is missing");
        if (!v.empty() && v.size() != 3)
            throw usage("[MultiRobotVSLAM] " + key + " must be 'x y yaw_deg'");
        startPoses.push_back(v.empty() ? mrpt::math::TPose2D()
                                       : mrpt::math::TPose2D(v[0], v[1], mrpt::DEG2RAD(v[2])));
    }
    if (pf.m_options.sampleSize < 1) throw usage("[ParticleFilter] sampleSize must be >= 1");
    if (pf.m_options.adaptiveSampleSize)
        throw usage("[ParticleFilter] adaptiveSampleSize is not supported (use 0)");
    if (pf.m_options.PF_algorithm != mrpt::bayes::CParticleFilter::pfStandardProposal &&
        pf.m_options.PF_algorithm != mrpt::bayes::CParticleFilter::pfOptimalProposal)
        throw usage(
            "[ParticleFilter] PF_algorithm must be pfStandardProposal (Gil et al. 2010, "
            "Sec. 3.1) or pfOptimalProposal (FastSLAM 2.0 proposal per robot)");

    // Every particle's map comes from the .ini through MRPT's map registry.
    mrpt::maps::TSetOfMetricMapInitializers inits;
    try {
        inits.loadFromConfigFile(cfg, kMapSection);
    } catch (const std::exception& e) {
        throw usage(core::oneLineMessage(e));
    }
    mrpt::maps::CMultiMetricMap maps(inits);
    const auto map = maps.mapByClass<CVisualLandmarksMap>();
    if (!map || maps.maps.size() != 1)
        throw usage(std::string("[") + kMapSection +
                    "] must define exactly one map: visualLandmarksMap_count = 1");
    mapTemplate = *map;
    if (!odometryLabel.empty() && filterOptions.robots.size() != 1)
        throw usage(
            "[MultiRobotVSLAM] odometry_label is for one robot; a team's odometry is "
            "labelled <ROBOT>_ODOM");
    for (const auto& [former, key] : kMovedKeys)
        if (cfg.keyExists(kAppSection, former))
            throw usage(std::string("[MultiRobotVSLAM] ") + former + ": moved to [" +
                        kSmootherSection + "] " + key);
    cfg.throwIfUnreadKeys();
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
        groundTruth.back() = core::TumTrajectory::load(tum);
        found++;
        if (startFromGroundTruth && !groundTruth.back()->empty()) {
            const auto& p = groundTruth.back()->poses.front();
            startPoses[k] = {p.x, p.y, p.yaw};
        }
    }
    if (found == 0 && !args.groundTruth.empty())
        throw std::runtime_error(groundTruthPrefix +
                                 ".groundtruth_<ROBOT>.tum: no ground truth "
                                 "file found (--ground-truth)");
    if (startFromGroundTruth && found < filterOptions.robots.size())
        for (size_t k = 1; k < filterOptions.robots.size(); k++)
            if (!groundTruth[k] &&
                !cfg.keyExists(kAppSection, "start_pose_" + filterOptions.robots[k]))
                throw core::UsageError(cfg.name() + ": [MultiRobotVSLAM] no ground truth for " +
                                       filterOptions.robots[k] + ": give start_pose_" +
                                       filterOptions.robots[k] + " = x y yaw_deg");
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
            throw std::runtime_error(rawlog + ": step " + std::to_string(steps) + ": cannot use " +
                                     stereo->sensorLabel + ": " + core::oneLineMessage(e));
        }
        // the images' landmarks replace any the frame had
        ObservationSelector::of<mrpt::obs::CObservationVisualLandmarks>(landmarksLabel)
            .eraseFrom(sf);
        landmarks->sensorLabel = landmarksLabel.empty() ? stereo->sensorLabel : landmarksLabel;
        sf.insert(landmarks);
        stereo->imageLeft.unload();
        stereo->imageRight.unload();
        landmarkObservations++;
    }
}

mrpt::obs::CActionCollection::Ptr MultiRobotVSLAMApp::Impl::singleRobotAction(
    const mrpt::obs::CActionCollection& actions, const mrpt::obs::CSensoryFrame& frame)
{
    const auto move = actions.getBestMovementEstimation();
    auto one = mrpt::obs::CActionCollection::Create();
    if (!move) return one;  // the filter names what is missing
    mrpt::obs::CActionRobotMovement2D copy(*move);
    if (copy.timestamp == INVALID_TIMESTAMP)
        for (const auto& obs : frame)
            if (obs && obs->timestamp != INVALID_TIMESTAMP) {
                copy.timestamp = obs->timestamp;
                break;
            }
    one->insert(copy);
    return one;
}

void MultiRobotVSLAMApp::initialize()
{
    auto& d = *m_impl;
    d.loadConfig();
    if (!mrpt::system::fileExists(d.rawlog))
        throw std::runtime_error(d.rawlog + ": cannot open rawlog");
    d.findGroundTruth();
    outDir = d.args.outDir;
    robots = d.filterOptions.robots;
    d.filter =
        std::make_unique<CMultiRobotVisualSLAM>(d.mapTemplate, d.pf.m_options.sampleSize, d.seed);
    // CParticleFilter's resampling draws from MRPT's global generator.
    mrpt::random::getRandomGenerator().randomize(d.seed);
    d.filter->options = d.filterOptions;
    if (d.smootherOptions.map_along_path) {
        d.smoother = std::make_unique<TeamPathSmoother>(d.mapTemplate);
        d.smoother->options = d.smootherOptions;
        d.filter->setStepObserver(d.smoother.get());
    }
    d.pf.setVerbosityLevel(mrpt::system::LVL_ERROR);
    if (d.args.gui) d.window = std::make_unique<core::LiveView>("multirobot-vslam");
}

namespace {
/// A path of (timestamp, pose) as a trajectory, one pose per timestamp (the first kept).
core::TumTrajectory asTrajectory(const std::vector<std::pair<double, mrpt::math::TPose2D>>& path)
{
    core::TumTrajectory t;
    for (const auto& [time, p] : path)
        if (t.empty() || time > t.timestamps.back()) t.push_back(time, to3D(p));
    return t;
}
}  // namespace

core::TumTrajectory MultiRobotVSLAMApp::Impl::bestParticlePath(size_t robot) const
{
    return asTrajectory(CMultiRobotVisualSLAM::pathOf(filter->bestParticle(), robot));
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

void MultiRobotVSLAMApp::run()
{
    auto& d = *m_impl;
    core::OutputDirectory out(outDir);
    core::RunTimer timer;
    core::RawlogReader reader(d.rawlog);
    core::ProgressReporter progress("multirobot-vslam", 0, d.args.quiet);

    using core::ObservationSelector;
    const auto& o = d.filterOptions;
    std::vector<ObservationSelector> steps;
    std::vector<std::string> odometryLabels;
    for (size_t k = 0; k < robots.size(); k++) {
        steps.push_back(ObservationSelector::of<mrpt::obs::CObservationVisualLandmarks>(
            o.inputLabel(k, o.landmarks_suffix)));
        steps.push_back(ObservationSelector::of<mrpt::obs::CObservationBearingRange>(
            o.inputLabel(k, o.range_bearing_suffix)));
        if (!o.robot_reading_ids.empty() && robots.size() > 1)
            steps.push_back(ObservationSelector::of<mrpt::obs::CObservationBearingRange>(
                robots[k] + o.robot_readings_suffix));
        steps.push_back(ObservationSelector::of<mrpt::obs::CObservationStereoImages>(
            o.inputLabel(k, "_STEREO")));
        if (robots.size() > 1) odometryLabels.push_back(robots[k] + "_ODOM");
    }
    if (robots.size() == 1 && !d.odometryLabel.empty()) odometryLabels = {d.odometryLabel};
    core::ActionFrameSource source(reader, steps, d.motionModel, odometryLabels);
    std::vector<mrpt::poses::CPose2D> odometry;
    for (const auto& p : d.startPoses) odometry.emplace_back(p);
    estimatedPaths.assign(robots.size(), {});
    odometryPaths.assign(robots.size(), {});
    mrpt::obs::CActionCollection::Ptr actions;
    mrpt::obs::CSensoryFrame::Ptr frame;
    while (source.next(actions, frame)) {
        if (robots.size() == 1) actions = d.singleRobotAction(*actions, *frame);
        d.prepareFrame(*frame);
        const double t = mrpt::Clock::toDouble(actions->begin()->get()->timestamp);
        if (d.steps == 0) d.filter->reset(d.startPoses, t);
        timer.startStep();
        try {
            d.pf.executeOn(*d.filter, actions.get(), frame.get());
        } catch (const std::exception& e) {
            throw std::runtime_error(d.rawlog + ": step " + std::to_string(d.steps) + ": " +
                                     core::oneLineMessage(e));
        }
        timer.endStep();

        for (size_t k = 0; k < robots.size(); k++) {
            const auto move =
                std::dynamic_pointer_cast<mrpt::obs::CActionRobotMovement2D>(actions->get(k));
            odometry[k] = odometry[k] + move->poseChange->getMeanVal();
            odometryPaths[k].push_back(t, to3D(odometry[k].asTPose()));
        }
        d.measurements += d.filter->lastStepStats.measurements;
        d.robotReadings += d.filter->lastStepStats.robot_readings;
        d.nonPositiveRanges += d.filter->lastStepStats.non_positive_ranges;
        progress.update(++d.steps);
        if (d.window)
            d.window->show([&](auto& scene) {
                std::vector<core::TumTrajectory> paths;
                for (size_t k = 0; k < robots.size(); k++) paths.push_back(d.bestParticlePath(k));
                d.drawTeam(scene, d.filter->bestParticle().map, paths);
            });
    }
    progress.finish(d.steps);
    std::string odoLabels;
    for (const auto& l : odometryLabels) odoLabels += (odoLabels.empty() ? "" : ", ") + l;
    const std::string inputs =
        robots.size() == 1
            ? "odometry (CActionRobotMovement2D, or CObservationOdometry" +
                  (odoLabels.empty() ? std::string() : " labelled " + odoLabels) +
                  ") and CObservationBearingRange, CObservationVisualLandmarks or "
                  "CObservationStereoImages" +
                  (o.sensor_label.empty() ? std::string() : " labelled " + o.sensor_label)
            : "observation-only rawlog with " + odoLabels + " and <ROBOT>" + o.landmarks_suffix +
                  ", <ROBOT>" + o.range_bearing_suffix + " or <ROBOT>_STEREO";
    if (d.steps == 0)
        throw std::runtime_error(d.rawlog + ": no steps (" + inputs +
                                 "); the rawlog has: " + reader.summary().describe());
    if (d.measurements == 0)
        throw std::runtime_error(d.rawlog + ": no landmark measurements (" + inputs +
                                 "); the rawlog has: " + reader.summary().describe());
    for (size_t k = 0; k < robots.size(); k++) estimatedPaths[k] = d.bestParticlePath(k);
    if (d.smootherOptions.smooth_paths) {
        const core::RunTimer smoothing;
        d.smoothed = d.smoother->smoothPaths(d.filter->bestParticle());
        d.smoothingSeconds = smoothing.elapsedSeconds();
        d.filterPaths = estimatedPaths;
        for (size_t k = 0; k < robots.size(); k++)
            estimatedPaths[k] = asTrajectory(d.smoothed->paths[k]);
    }
    d.writeOutputs(*this, timer);
    if (d.window && !d.args.quiet) d.window->waitUntilClosed();
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

void MultiRobotVSLAMApp::Impl::writeOutputs(MultiRobotVSLAMApp& app, const core::RunTimer& timer)
{
    core::OutputDirectory out(app.outDir);
    const auto& best = filter->bestParticle();
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
        alongPath = smoother->mapAlongPath(best, &alongPathCorrespondences);
        alongPathSeconds = rebuild.elapsedSeconds();
    }
    if (smootherOptions.map_along_path)
        best.map.saveMetricMapRepresentationToFile(out.file("particle_map"));
    const CVisualLandmarksMap& map = smoothed ? smoothed->map : alongPath ? *alongPath : best.map;
    // the correspondences `map` was made with
    const std::vector<TCorrespondence> correspondences =
        smoothed    ? smoothed->correspondences
        : alongPath ? alongPathCorrespondences
                    : TLandmarkIdentityTally::historyOf(best);
    core::saveFinalMap(map, app.outDir);

    mrpt::opengl::COpenGLScene scene;
    drawTeam(scene, map, app.estimatedPaths);
    for (size_t k = 0; k < app.robots.size(); k++) {
        scene.insert(core::trajectoryAsLines(app.odometryPaths[k], {0.9f, 0.1f, 0.1f},
                                             "odometry " + app.robots[k]));
        if (groundTruth[k])
            scene.insert(core::trajectoryAsLines(*groundTruth[k], {0, 0, 0},
                                                 "ground truth " + app.robots[k]));
    }
    const std::string landmarksFile = groundTruthPrefix + ".landmarks.txt";
    std::optional<core::LandmarkFile> trueLandmarks;
    if (mrpt::system::fileExists(landmarksFile)) {
        trueLandmarks = core::LandmarkFile::load(landmarksFile);
        std::vector<mrpt::math::TPoint3D> pts;
        for (const auto& lm : trueLandmarks->landmarks) pts.push_back(lm.position);
        scene.insert(core::pointsAsCrosses(pts, {0, 0, 0}));
    }
    core::saveScene(scene, out.file("final.3Dscene"));

    cfg.writeEffectiveConfig(out.file("config.ini"));
    core::RunReport report("multirobot-vslam");
    args.describeInputs(report, cfg.effectiveText(), rawlog, seed);
    report.setOpenCvVersion(CV_VERSION);
    report.setCount("robots", static_cast<double>(app.robots.size()));
    report.setCount("steps", static_cast<double>(steps));
    report.setCount("stereo_frames", static_cast<double>(stereoFrames));
    report.setCount("landmark_observations", static_cast<double>(landmarkObservations));
    report.setCount("measurements", static_cast<double>(measurements));
    report.setCount("robot_readings", static_cast<double>(robotReadings));
    report.setCount("readings_with_non_positive_range", static_cast<double>(nonPositiveRanges));
    if (nonPositiveRanges > 0 && !args.quiet)
        std::printf("multirobot-vslam: %zu range-bearing readings with a range <= 0 left out\n",
                    nonPositiveRanges);
    report.setCount("particles", static_cast<double>(filter->particlesCount()));
    report.setCount("landmarks", static_cast<double>(map.size()));
    if (smootherOptions.map_along_path)
        report.setCount("particle_map_landmarks", static_cast<double>(best.map.size()));
    if (alongPath) report.setResult("map_along_path_s", alongPathSeconds);
    if (smoothed) {
        report.setResult("smoothing_s", smoothingSeconds);
        report.setCount("smoothing_iterations", static_cast<double>(smoothed->iterations));
        report.setCount("smoothing_outlier_readings",
                        static_cast<double>(smoothed->outlier_readings));
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
    report.setTiming(timer);
    if (trueLandmarks)
        report.setResultJson("landmark_merging", landmarkMergingJson(map, *trueLandmarks));
    if (const auto a = identityAssociationJson(TLandmarkIdentityTally::of(correspondences, map));
        !a.empty())
        report.setResultJson("association_by_identity", a);
    bool anyGroundTruth = false;
    for (const auto& g : groundTruth) anyGroundTruth = anyGroundTruth || g.has_value();
    if (anyGroundTruth) report.setGroundTruth(groundTruthPrefix);
    report.write(out.file("run.json"));

    if (anyGroundTruth) {
        core::TEvalParams eval;
        eval.run_dir = app.outDir;
        eval.ground_truth = groundTruthPrefix;
        core::evaluateRunFolder(eval);
    }
}

}  // namespace mrpt_vslam::multirobot
