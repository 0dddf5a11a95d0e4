#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/maps/TMetricMapInitializer.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt/system/filesystem.h>
#include <mrpt_vslam/apps/LiveView.h>
#include <mrpt_vslam/apps/OmniFastSLAMApp.h>
#include <mrpt_vslam/core/ActionFrameSource.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/ObservationSelector.h>
#include <mrpt_vslam/core/OutputDirectory.h>
#include <mrpt_vslam/core/PajdlaBaksteinCamera.h>
#include <mrpt_vslam/core/ProgressReporter.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/RunEvaluation.h>
#include <mrpt_vslam/core/RunOutputs.h>
#include <mrpt_vslam/core/RunReport.h>
#include <mrpt_vslam/core/RunTimer.h>
#include <mrpt_vslam/core/SingleRobotStart.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/omni_fastslam/COmniFastSLAM.h>
#include <mrpt_vslam/omni_fastslam/CeilingLightDetector.h>

#include <cstdio>
#include <opencv2/core/version.hpp>
#include <optional>
#include <stdexcept>

namespace mrpt_vslam::apps {

using omni_fastslam::CCeilingLightsMap;
using omni_fastslam::CeilingLightDetector;
using omni_fastslam::COmniFastSLAM;

namespace {
constexpr const char* kAppSection = "OmniFastSLAM";
constexpr const char* kMapSection = "MappingApplication";

/// Where the light measurements come from (ini key `input`).
enum class TInput { Auto, Bearings, Images };

mrpt::math::TPose3D to3D(const mrpt::math::TPose2D& p) { return {p.x, p.y, 0, p.phi, 0, 0}; }
}  // namespace

struct OmniFastSLAMApp::Impl {
    core::AppArguments args;
    core::CheckedConfigFile cfg;
    std::string rawlog;
    uint32_t seed = 1;
    TInput input = TInput::Auto;
    std::string imageLabel = "OMNICAM";
    /// One robot of a multi-robot rawlog (ini `robot`): labels <ROBOT>_ODOM and <ROBOT>_RB,
    /// outputs and ground truth with the _<ROBOT> suffix. Empty: a single-robot rawlog.
    std::string robot;
    core::SingleRobotStart start;

    mrpt::bayes::CParticleFilter pf;
    CCeilingLightsMap mapTemplate;
    COmniFastSLAM::TOptions filterOptions;
    core::PajdlaBaksteinCamera camera;
    CeilingLightDetector::TOptions detectorOptions;
    std::unique_ptr<CeilingLightDetector> detector;
    std::unique_ptr<COmniFastSLAM> filter;
    /// Motion model of the actions built for observation-only rawlogs ([MotionModel]).
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions motionModel;

    size_t frames = 0, framesWithImages = 0, measurements = 0;

    void loadConfig();
    /// Measurements from the frame's image when images are the input (Sec. III-A).
    void prepareFrame(mrpt::obs::CSensoryFrame& sf);
    void writeOutputs(OmniFastSLAMApp& app, const core::RunTimer& timer);
    /// The scene of the best particle: map with ellipsoids and its path (final.3Dscene, --gui).
    void drawBestParticle(mrpt::opengl::COpenGLScene& scene) const;

    std::unique_ptr<LiveView> window;  ///< --gui
};

OmniFastSLAMApp::OmniFastSLAMApp(core::AppArguments args) : m_impl(std::make_unique<Impl>())
{
    m_impl->args = std::move(args);
}

OmniFastSLAMApp::~OmniFastSLAMApp() = default;

void OmniFastSLAMApp::Impl::loadConfig()
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
    else if (in == "bearings")
        input = TInput::Bearings;
    else if (in == "images")
        input = TInput::Images;
    else
        throw usage("[OmniFastSLAM] input must be auto, bearings or images, not '" + in + "'");
    imageLabel = cfg.read_string(kAppSection, "image_label", imageLabel);
    robot = cfg.read_string(kAppSection, "robot", "");
    start.loadFromConfig(cfg, kAppSection);

    try {
        filterOptions.loadFromConfigFile(cfg, kAppSection);
        if (!robot.empty()) filterOptions.bearings_label = robot + "_RB";
        pf.m_options.loadFromConfigFile(cfg, "ParticleFilter");
        camera.loadFromConfigFile(cfg, "Camera");
        detectorOptions.loadFromConfigFile(cfg, "LightDetector");
    } catch (const core::UsageError&) {
        throw;
    } catch (const std::exception& e) {
        throw usage(mrpt::exception_to_str(e));
    }
    if (pf.m_options.sampleSize < 1) throw usage("[ParticleFilter] sampleSize must be >= 1");
    if (pf.m_options.adaptiveSampleSize)
        throw usage("[ParticleFilter] adaptiveSampleSize is not supported (use 0)");
    using PF = mrpt::bayes::CParticleFilter;
    if (pf.m_options.PF_algorithm != PF::pfOptimalProposal &&
        pf.m_options.PF_algorithm != PF::pfStandardProposal)
        throw usage(
            "[ParticleFilter] PF_algorithm must be pfOptimalProposal (FastSLAM 2.0) or "
            "pfStandardProposal (FastSLAM 1.0)");

    // [MotionModel]: MRPT's Gaussian model, used for observation-only rawlogs
    try {
        motionModel = core::ActionFrameSource::loadMotionModel(cfg, "MotionModel");
    } catch (const core::UsageError& e) {
        throw usage(e.what());
    }

    // Every particle's map comes from the .ini through MRPT's map registry.
    mrpt::maps::TSetOfMetricMapInitializers inits;
    inits.loadFromConfigFile(cfg, kMapSection);
    mrpt::maps::CMultiMetricMap maps(inits);
    const auto lights = maps.mapByClass<CCeilingLightsMap>();
    if (!lights || maps.maps.size() != 1)
        throw usage(std::string("[") + kMapSection +
                    "] must define exactly one map: ceilingLightsMap_count = 1");
    mapTemplate = *lights;
    cfg.throwIfUnreadKeys();
}

void OmniFastSLAMApp::Impl::prepareFrame(mrpt::obs::CSensoryFrame& sf)
{
    using core::ObservationSelector;
    const auto image = ObservationSelector::firstIn<mrpt::obs::CObservationImage>(sf, imageLabel);
    const bool hasBearings =
        static_cast<bool>(ObservationSelector::firstIn<mrpt::obs::CObservationBearingRange>(
            sf, filterOptions.bearings_label));
    if (image) framesWithImages++;
    if (input == TInput::Bearings || (input == TInput::Auto && hasBearings)) return;
    if (!image) return;
    if (!detector) detector = std::make_unique<CeilingLightDetector>(camera, detectorOptions);
    mrpt::obs::CObservationBearingRange::Ptr bearings;
    try {
        bearings = detector->detect(*image, filterOptions.bearings_label);
    } catch (const std::exception& e) {
        const auto& img = image->image;
        throw std::runtime_error(rawlog + ": frame " + std::to_string(frames) +
                                 ": cannot use the " + imageLabel + " image" +
                                 (img.isExternallyStored()
                                      ? " '" + img.getExternalStorageFileAbsolutePath() + "'"
                                      : std::string()) +
                                 ": " + core::oneLineMessage(e));
    }
    // the image's bearings replace any the frame had
    ObservationSelector::of<mrpt::obs::CObservationBearingRange>(filterOptions.bearings_label)
        .eraseFrom(sf);
    sf.insert(bearings);
    image->unload();
}

void OmniFastSLAMApp::initialize()
{
    auto& d = *m_impl;
    d.loadConfig();
    if (!mrpt::system::fileExists(d.rawlog))
        throw std::runtime_error(d.rawlog + ": cannot open rawlog");
    d.start.resolve(d.args, d.rawlog, d.robot);
    outDir = d.args.outDir;
    d.filter = std::make_unique<COmniFastSLAM>(d.mapTemplate, d.pf.m_options.sampleSize, d.seed);
    // CParticleFilter's resampling draws from MRPT's global generator.
    mrpt::random::getRandomGenerator().randomize(d.seed);
    d.filter->options = d.filterOptions;
    d.pf.setVerbosityLevel(mrpt::system::LVL_ERROR);
    if (d.args.gui) d.window = std::make_unique<LiveView>("omni-fastslam");
}

void OmniFastSLAMApp::Impl::drawBestParticle(mrpt::opengl::COpenGLScene& scene) const
{
    const auto& best = filter->bestParticle();
    core::TumTrajectory path;
    for (const auto& [t, p] : COmniFastSLAM::pathOf(best)) path.push_back(t, to3D(p));
    scene.insert(mrpt::opengl::CGridPlaneXY::Create(-10, 40, -15, 15, 0, 1));
    scene.insert(best.map.getVisualization());
    scene.insert(core::trajectoryAsLines(path, {0, 0.8f, 0}, "estimate"));
}

void OmniFastSLAMApp::run()
{
    auto& d = *m_impl;
    core::OutputDirectory out(outDir);
    core::RunTimer timer;
    core::RawlogReader reader(d.rawlog);
    core::ProgressReporter progress("omni-fastslam", 0, d.args.quiet);

    using core::ObservationSelector;
    core::ActionFrameSource source(
        reader,
        {ObservationSelector::of<mrpt::obs::CObservationBearingRange>(
             d.filterOptions.bearings_label),
         ObservationSelector::of<mrpt::obs::CObservationImage>(d.imageLabel)},
        d.motionModel,
        d.robot.empty() ? std::vector<std::string>{} : std::vector<std::string>{d.robot + "_ODOM"});
    mrpt::poses::CPose2D odometry(d.start.pose);
    bool started = false;
    mrpt::obs::CActionCollection::Ptr actions;
    mrpt::obs::CSensoryFrame::Ptr frame;
    while (source.next(actions, frame)) {
        d.prepareFrame(*frame);
        const double t = mrpt::Clock::toDouble(frame->size() ? (*frame->begin())->timestamp
                                                             : actions->begin()->get()->timestamp);
        if (!started) {
            d.filter->reset(d.start.pose, t);
            started = true;
        }
        timer.startStep();
        try {
            d.pf.executeOn(*d.filter, actions.get(), frame.get());
        } catch (const std::exception& e) {
            throw std::runtime_error(d.rawlog + ": step " + std::to_string(d.frames) + ": " +
                                     core::oneLineMessage(e));
        }
        timer.endStep();

        odometry = odometry + actions->getBestMovementEstimation()->poseChange->getMeanVal();
        odometryPath.push_back(t, to3D(odometry.asTPose()));
        d.measurements += d.filter->lastStepStats.measurements;
        progress.update(++d.frames);
        if (d.window) d.window->show([&](auto& scene) { d.drawBestParticle(scene); });
    }
    progress.finish(d.frames);
    if (d.frames == 0)
        throw std::runtime_error(d.rawlog +
                                 ": no frames with odometry (action / sensory-frame pairs, or "
                                 "CObservationOdometry with " +
                                 d.filterOptions.bearings_label + " or " + d.imageLabel +
                                 "); the rawlog has: " + reader.summary().describe());
    if (d.measurements == 0)
        throw std::runtime_error(d.rawlog + ": no ceiling-light measurements (" +
                                 d.filterOptions.bearings_label + " or " + d.imageLabel +
                                 "); the rawlog has: " + reader.summary().describe());
    for (const auto& [t, p] : COmniFastSLAM::pathOf(d.filter->bestParticle()))
        if (estimatedPath.empty() || t > estimatedPath.timestamps.back())
            estimatedPath.push_back(t, to3D(p));
    d.writeOutputs(*this, timer);
    if (d.window && !d.args.quiet) d.window->waitUntilClosed();
}

void OmniFastSLAMApp::Impl::writeOutputs(OmniFastSLAMApp& app, const core::RunTimer& timer)
{
    core::OutputDirectory out(app.outDir);
    const auto& best = filter->bestParticle();
    const std::string suffix = robot.empty() ? "" : "_" + robot;
    app.estimatedPath.save(out.file("estimated_path" + suffix + ".tum"),
                           "omni-fastslam: best particle's path");
    app.odometryPath.save(out.file("odometry_path" + suffix + ".tum"),
                          "omni-fastslam: dead reckoning");
    core::saveFinalMap(best.map, app.outDir);

    mrpt::opengl::COpenGLScene scene;
    drawBestParticle(scene);
    scene.insert(core::trajectoryAsLines(app.odometryPath, {0.9f, 0.1f, 0.1f}, "odometry"));
    if (start.groundTruth)
        scene.insert(core::trajectoryAsLines(*start.groundTruth, {0, 0, 0}, "ground truth"));
    const std::string landmarksFile = start.groundTruthPrefix + ".landmarks.txt";
    if (mrpt::system::fileExists(landmarksFile)) {
        std::vector<mrpt::math::TPoint3D> pts;
        for (const auto& lm : core::LandmarkFile::load(landmarksFile).landmarks)
            pts.push_back(lm.position);
        scene.insert(core::pointsAsCrosses(pts, {0, 0, 0}));
    }
    core::saveScene(scene, out.file("final.3Dscene"));

    cfg.writeEffectiveConfig(out.file("config.ini"));
    core::RunReport report("omni-fastslam");
    args.describeInputs(report, cfg.effectiveText(), rawlog, seed);
    report.setOpenCvVersion(CV_VERSION);
    report.setCount("frames", frames);
    report.setCount("frames_with_images", framesWithImages);
    report.setCount("measurements", measurements);
    report.setCount("particles", filter->particlesCount());
    report.setCount("landmarks", best.map.landmarks().size());
    report.setCount("candidates", best.map.candidates().size());
    report.setTiming(timer);
    // which camera pose the measurement model used: the config's, or the observations' own
    const auto& pose = best.map.sensorPoseInUse();
    const bool configured = best.map.sensorOptions.sensor_in_robot.has_value();
    report.setResultJson("camera_pose_on_robot",
                         mrpt::format("{\"source\": \"%s\", \"x_y_z_m_yaw_pitch_roll_deg\": "
                                      "[%g, %g, %g, %g, %g, %g]}",
                                      configured ? "config" : "observations", pose.x(), pose.y(),
                                      pose.z(), mrpt::RAD2DEG(pose.yaw()),
                                      mrpt::RAD2DEG(pose.pitch()), mrpt::RAD2DEG(pose.roll())));
    if (!args.quiet)
        std::printf("omni-fastslam: camera pose on the robot from the %s: %s\n",
                    configured ? "config (sensor_in_robot)" : "observations",
                    pose.asString().c_str());
    if (best.associations.labelled() > 0) {
        // evaluation only: the rawlog gave landmark numbers (landmarkID), the filter ignored them
        report.setResult("labelled_associations", best.associations.labelled());
        report.setResult("wrong_associations", best.associations.wrong());
        // per map landmark id: the landmark numbers of the measurements associated to it
        std::string table = "{";
        for (const auto& [landmark, ids] : best.associations.counts) {
            table += (table.size() > 1 ? ", \"" : "\"") + std::to_string(landmark) + "\": {";
            bool first = true;
            for (const auto& [id, count] : ids) {
                table +=
                    (first ? "\"" : ", \"") + std::to_string(id) + "\": " + std::to_string(count);
                first = false;
            }
            table += "}";
        }
        report.setResultJson("associations_by_landmark", table + "}");
    }
    if (start.groundTruth) report.setGroundTruth(start.groundTruthPrefix);
    report.write(out.file("run.json"));

    if (start.groundTruth) {
        core::TEvalParams eval;
        eval.run_dir = app.outDir;
        eval.ground_truth = start.groundTruthPrefix;
        core::evaluateRunFolder(eval);
    }
}

}  // namespace mrpt_vslam::apps
