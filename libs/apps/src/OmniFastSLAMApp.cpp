#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/apps/OmniFastSLAMApp.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/KLDSampling.h>
#include <mrpt_vslam/core/ObservationSelector.h>
#include <mrpt_vslam/core/PajdlaBaksteinCamera.h>
#include <mrpt_vslam/core/PajdlaBaksteinFit.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/RunOutputs.h>
#include <mrpt_vslam/core/SingleRobotStart.h>
#include <mrpt_vslam/omni_fastslam/COmniFastSLAM.h>
#include <mrpt_vslam/omni_fastslam/CeilingLightDetector.h>
#include <mrpt_vslam/omni_fastslam/LightsPathSmoother.h>

#include <cstdio>
#include <stdexcept>

#include "ImagesCameraModel.h"
#include "ParticleFilterApp.h"

namespace mrpt_vslam::apps {

using omni_fastslam::CCeilingLightsMap;
using omni_fastslam::CeilingLightDetector;
using omni_fastslam::COmniFastSLAM;
using omni_fastslam::LightsPathSmoother;

namespace {
constexpr const char* kAppSection = kOmniFastSLAMId.section;
constexpr const char* kSmootherSection = "LightsPathSmoother";

/// Where the light measurements come from (ini key `input`).
enum class TInput { Auto, Bearings, Images };
}  // namespace

struct OmniFastSLAMApp::Impl : ParticleFilterApp {
    Impl(OmniFastSLAMApp& owner, core::AppArguments arguments)
        : ParticleFilterApp(std::move(arguments), kOmniFastSLAMId.name, kAppSection), app(owner)
    {
    }

    OmniFastSLAMApp& app;  ///< where the results go
    TInput input = TInput::Auto;
    std::string imageLabel = "OMNICAM";
    /// One robot of a multi-robot rawlog (ini `robot`): labels <ROBOT>_ODOM and <ROBOT>_RB,
    /// outputs and ground truth with the _<ROBOT> suffix. Empty: a single-robot rawlog.
    std::string robot;
    core::SingleRobotStart start;

    CCeilingLightsMap mapTemplate;
    COmniFastSLAM::TOptions filterOptions;
    core::TKLDParams kld;
    /// the detector's camera: [Camera], or the images' calibration fitted (camera_model)
    std::optional<ImagesCameraModel<core::PajdlaBaksteinCamera>> cameraModel;
    CeilingLightDetector::TOptions detectorOptions;
    std::unique_ptr<CeilingLightDetector> detector;
    LightsPathSmoother::TOptions smootherOptions;
    /// Independent filters run side by side; the one whose smoothed solution costs least is kept.
    size_t filterRuns = 1;
    /// Its smoother records the run: the smoothing (with smooth_path) and the camera pose check.
    using Run = TFilterRun<COmniFastSLAM, LightsPathSmoother>;
    /// filter_runs of them, from the seeds --seed, --seed + 1, ...; after endSteps() the kept one
    std::vector<Run> runs;
    /// The first run during the steps (its figures stand for all: they read the same data), the
    /// kept one after endSteps().
    COmniFastSLAM& filter() const { return *runs.front().filter; }
    const LightsPathSmoother& smoother() const { return *runs.front().smoother; }
    /// With smooth_path, per run (by seed): what its smoothing gave.
    std::vector<TRunOutcome> runOutcomes;
    size_t keptRun = 0;  ///< of runOutcomes
    /// With smooth_path: the smoothed path and lights, the time they took, the filter's path.
    std::optional<LightsPathSmoother::TResult> smoothed;
    double smoothingSeconds = 0;
    core::TumTrajectory filterPath;
    mrpt::poses::CPose2D odometry;  ///< dead reckoning from the start pose

    size_t framesWithImages = 0, measurements = 0;
    /// Frames whose bearings the filter took, and frames whose image the detector searched.
    size_t framesWithBearingsUsed = 0, imagesSearched = 0;

    /// Measurements from the frame's image when images are the input (Sec. III-A).
    void prepareFrame(mrpt::obs::CSensoryFrame& sf);
    /// run.json `camera_model` and its line: which model the detector used.
    void reportCameraModel(core::RunReport& report) const;
    /// The scene of the best particle: map with ellipsoids and its path (final.3Dscene, --gui).
    void drawBestParticle(mrpt::opengl::COpenGLScene& scene) const;

    void loadConfig() override;
    void prepare() override;
    std::vector<core::ObservationSelector> stepObservations() const override;
    std::vector<std::string> odometryLabels() const override;
    void step(mrpt::obs::CActionCollection::Ptr actions, mrpt::obs::CSensoryFrame& frame,
              core::RunTimer& timer) override;
    void drawLive(mrpt::opengl::COpenGLScene& scene) const override { drawBestParticle(scene); }
    void endSteps(const core::TRawlogSummary& contents) override;
    void writeResults(const core::OutputDirectory& out, mrpt::opengl::COpenGLScene& scene,
                      core::RunReport& report) override;
    std::optional<std::string> groundTruthName() const override;
};

OmniFastSLAMApp::OmniFastSLAMApp(core::AppArguments args)
    : outDir(args.outDir), m_impl(std::make_unique<Impl>(*this, std::move(args)))
{
}

OmniFastSLAMApp::~OmniFastSLAMApp() = default;

void OmniFastSLAMApp::initialize() { m_impl->initialize(); }

void OmniFastSLAMApp::run() { m_impl->run(); }

std::vector<core::TReadKey> OmniFastSLAMApp::configKeys() const { return m_impl->configKeys(); }

void OmniFastSLAMApp::Impl::loadConfig()
{
    input = readChoice<TInput>(
        "input",
        {{"auto", TInput::Auto}, {"bearings", TInput::Bearings}, {"images", TInput::Images}});
    imageLabel = cfg.read_string(kAppSection, "image_label", imageLabel);
    const bool cameraFromImages = readChoice<bool>("camera_model", kCameraModelChoices);
    robot = cfg.read_string(kAppSection, "robot", "");
    start.loadFromConfig(cfg, kAppSection);

    try {
        filterOptions.loadFromConfigFile(cfg, kAppSection);
        if (!robot.empty()) filterOptions.bearings_label = robot + "_RB";
        kld.loadFromConfigFile(cfg, "KLD_options");
        smootherOptions.loadFromConfigFile(cfg, kSmootherSection);
        try {
            core::validateKLDParams(kld);
        } catch (const std::invalid_argument& e) {
            throw usageError(std::string("[KLD_options] ") + e.what());
        }
        core::PajdlaBaksteinCamera config;
        config.loadFromConfigFile(cfg, "Camera");
        cameraModel.emplace(cameraFromImages, config, core::fitPajdlaBakstein);
        detectorOptions.loadFromConfigFile(cfg, "LightDetector");
    } catch (const core::UsageError&) {
        throw;
    } catch (const std::exception& e) {
        throw configError(e);
    }
    filterRuns = loadFilterRuns(filterRuns, smootherOptions.smooth_path,
                                "[" + std::string(kSmootherSection) + "] smooth_path");
    loadParticleFilterOptions(true);
    mapTemplate = particleMapTemplate<CCeilingLightsMap>("ceilingLightsMap_count");
}

void OmniFastSLAMApp::Impl::prepare()
{
    start.resolve(args, rawlog, robot);
    for (size_t run = 0; run < filterRuns; run++) {
        Run r{makeFilter<COmniFastSLAM>(mapTemplate, static_cast<uint32_t>(run)),
              std::make_unique<LightsPathSmoother>()};
        r.filter->options = filterOptions;
        r.filter->kld = kld;
        r.smoother->options = smootherOptions;
        r.filter->setStepObserver(r.smoother.get());
        runs.push_back(std::move(r));
    }
}

std::vector<core::ObservationSelector> OmniFastSLAMApp::Impl::stepObservations() const
{
    using core::ObservationSelector;
    // one camera: its model, and the bearings of one frame (measurementsFromFrame)
    return {ObservationSelector::ofOneSensor<mrpt::obs::CObservationBearingRange>(
                filterOptions.bearings_label, ownKey("bearings_label")),
            ObservationSelector::ofOneSensor<mrpt::obs::CObservationImage>(imageLabel,
                                                                           ownKey("image_label"))};
}

std::vector<std::string> OmniFastSLAMApp::Impl::odometryLabels() const
{
    if (robot.empty()) return {};
    return {robot + "_ODOM"};
}

void OmniFastSLAMApp::Impl::prepareFrame(mrpt::obs::CSensoryFrame& sf)
{
    using core::ObservationSelector;
    const auto image = ObservationSelector::firstIn<mrpt::obs::CObservationImage>(sf, imageLabel);
    const bool hasBearings =
        static_cast<bool>(ObservationSelector::firstIn<mrpt::obs::CObservationBearingRange>(
            sf, filterOptions.bearings_label));
    if (image) framesWithImages++;
    if (input == TInput::Bearings || (input == TInput::Auto && hasBearings)) {
        if (hasBearings) framesWithBearingsUsed++;
        return;
    }
    // images are the input: the frame's bearings are not used, with an image or without
    ObservationSelector::of<mrpt::obs::CObservationBearingRange>(filterOptions.bearings_label)
        .eraseFrom(sf);
    if (!image) return;
    imagesSearched++;
    mrpt::obs::CObservationBearingRange::Ptr bearings;
    try {
        const auto& model = cameraModel->of(image->cameraParams);
        if (!detector) detector = std::make_unique<CeilingLightDetector>(model, detectorOptions);
        bearings = detector->detect(*image, filterOptions.bearings_label);
    } catch (const std::exception& e) {
        const std::string file = core::RawlogReader::describeExternalImage(image->image, rawlog);
        throw std::runtime_error(rawlog + ": frame " + std::to_string(steps) + ": cannot use " +
                                 ObservationSelector::nameOf(*image) +
                                 (file.empty() ? "" : " " + file) + ": " + core::oneLineMessage(e));
    }
    sf.insert(bearings);
    image->unload();
}

void OmniFastSLAMApp::Impl::reportCameraModel(core::RunReport& report) const
{
    if (!cameraModel->model()) return;  // no image searched
    const core::PajdlaBaksteinCamera& model = *cameraModel->model();
    const std::string line = cameraModel->report(report, kOmniFastSLAMId.name, "fisheye",
                                                 {{"a", model.a},
                                                  {"b", model.b},
                                                  {"c", model.c},
                                                  {"d", model.d},
                                                  {"u0", model.u0},
                                                  {"v0", model.v0},
                                                  {"beta", model.beta}},
                                                 args.quiet);
    if (const auto* fit = cameraModel->fit(); fit && fit->max_error_px > detectorOptions.pixel_std)
        report.addWarning(
            line + mrpt::format(", more than [LightDetector] pixel_std = %g px: lower [Camera] "
                                "max_theta_deg to the lens's field of view, or give its model "
                                "in [Camera] with camera_model = config (doc/camera-model.md)",
                                detectorOptions.pixel_std));
}

void OmniFastSLAMApp::Impl::drawBestParticle(mrpt::opengl::COpenGLScene& scene) const
{
    const auto& best = filter().bestParticle();
    core::TumTrajectory path;
    for (const auto& [t, p] : COmniFastSLAM::pathOf(best))
        path.push_back(t, mrpt::math::TPose3D(p));
    scene.insert(mrpt::opengl::CGridPlaneXY::Create(-10, 40, -15, 15, 0, 1));
    scene.insert(best.map.getVisualization());
    scene.insert(core::trajectoryAsLines(path, {0, 0.8f, 0}, "estimate"));
}

void OmniFastSLAMApp::Impl::step(mrpt::obs::CActionCollection::Ptr actions,
                                 mrpt::obs::CSensoryFrame& frame, core::RunTimer& timer)
{
    prepareFrame(frame);
    const double t =
        stepTime(frame.size() ? (*frame.begin())->timestamp : actions->begin()->get()->timestamp);
    if (steps == 0) {
        const auto move = actions->getBestMovementEstimation();  // none: the filter says so
        odometry = mrpt::poses::CPose2D(start.atFirstStep(
            t, move ? move->poseChange->getMeanVal().asTPose() : mrpt::math::TPose2D()));
        for (auto& run : runs) run.filter->reset(start.pose, t);
    }
    filterStep(*actions, frame, timer);

    odometry = odometry + actions->getBestMovementEstimation()->poseChange->getMeanVal();
    app.odometryPath.push_back(t, mrpt::math::TPose3D(odometry.asTPose()));
    measurements += filter().lastStepStats.measurements;
}

void OmniFastSLAMApp::Impl::endSteps(const core::TRawlogSummary& contents)
{
    using core::ObservationSelector;
    const std::string bearings =
        ObservationSelector::of<mrpt::obs::CObservationBearingRange>(filterOptions.bearings_label)
            .describe();
    const std::string images =
        ObservationSelector::of<mrpt::obs::CObservationImage>(imageLabel).describe();
    const std::string inputs = input == TInput::Bearings ? bearings
                               : input == TInput::Images ? images
                                                         : bearings + " or " + images;
    if (steps == 0) throw noFramesError(inputs, contents);
    if (measurements == 0 && framesWithBearingsUsed + imagesSearched == 0)
        throw std::runtime_error(rawlog + ": no ceiling-light measurements (" + inputs +
                                 "); the rawlog has: " + contents.describe());
    if (measurements == 0) {  // there were bearings or images, but no light in them
        std::string why;
        if (framesWithBearingsUsed > 0)
            why = "the " + std::to_string(framesWithBearingsUsed) + " frames' " + bearings +
                  " hold no bearing";
        if (imagesSearched > 0)
            why += (why.empty() ? "" : "; ") + std::string("no light was detected in the ") +
                   std::to_string(imagesSearched) + " images (" + images +
                   "): check [LightDetector] intensity_threshold, min_blob_area, max_blob_area "
                   "and [Camera] (doc/omni-fastslam.md)";
        throw std::runtime_error(rawlog + ": no ceiling-light measurement in any frame: " + why);
    }
    if (smootherOptions.smooth_path) {
        const core::RunTimer smoothing;
        auto results = keepCheapestRun(
            runs, [](const Run& r) { return r.smoother->smooth(r.filter->bestParticle()); },
            [](const LightsPathSmoother::TResult& s) { return s.final_cost; }, keptRun);
        for (const auto& s : results)
            runOutcomes.push_back({s.final_cost, s.map.landmarks().size(), s.bearings});
        smoothed = std::move(results[keptRun]);
        smoothingSeconds = smoothing.elapsedSeconds();
    }
    app.estimatedPath = asTrajectory(COmniFastSLAM::pathOf(filter().bestParticle()));
    if (smoothed) {
        filterPath = app.estimatedPath;
        app.estimatedPath = asTrajectory(smoothed->path);
    }
}

void OmniFastSLAMApp::Impl::writeResults(const core::OutputDirectory& out,
                                         mrpt::opengl::COpenGLScene& scene, core::RunReport& report)
{
    const auto& best = filter().bestParticle();
    const std::string suffix = robot.empty() ? "" : "_" + robot;
    app.estimatedPath.save(
        out.file("estimated_path" + suffix + ".tum"),
        smoothed ? "omni-fastslam: smoothed path" : "omni-fastslam: best particle's path");
    app.odometryPath.save(out.file("odometry_path" + suffix + ".tum"),
                          "omni-fastslam: dead reckoning");
    if (smoothed) {
        filterPath.save(out.file("filter_path" + suffix + ".tum"),
                        "omni-fastslam: best particle's path, before smoothing");
        core::saveFinalMap(smoothed->map, out.path());
        core::saveMapFiles(best.map, out.path(), "filter_map");
        scene.insert(smoothed->map.getVisualization());
        scene.insert(core::trajectoryAsLines(app.estimatedPath, {0, 0.8f, 0}, "smoothed"));
        scene.insert(core::trajectoryAsLines(filterPath, {0.6f, 0.8f, 0.6f}, "filter"));
        report.setResultJson(
            "smoothing",
            mrpt::format("{\"iterations\": %zu, \"bearings\": %zu, \"outliers\": %zu, "
                         "\"merged_lights\": %zu, \"lights_with_filter_covariance\": %zu, "
                         "\"initial_cost\": %.17g, \"final_cost\": %.17g}",
                         smoothed->iterations, smoothed->bearings, smoothed->outliers,
                         smoothed->merged, smoothed->lights_with_filter_covariance,
                         smoothed->initial_cost, smoothed->final_cost));
        report.setPartTiming("smoothing", smoothingSeconds);
        reportFilterRuns(runOutcomes, keptRun, report);
        // the shipped halls leave 1 in 200 beyond 3 σ, MRCLAM's bearings 1 in 48-107; a camera
        // yaw 90° off or images of no ceiling lights, three quarters and more; stock
        // simul-landmarks lights at random, a quarter where close lights were mixed up
        if (10 * smoothed->outliers > smoothed->bearings)
            report.addWarning(mrpt::format(
                "after smoothing, %zu of the %zu bearings lie beyond %g sigma of their lights "
                "(about 1 in %.0f would with the camera right): check %s and the camera pose "
                "on the robot, or lights closer to each other than the bearings' noise tells "
                "apart; filter_path%s.tum holds the filter's own path (doc/omni-fastslam.md)",
                smoothed->outliers, smoothed->bearings, smootherOptions.huber,
                1 / smoothed->outlier_probability, cameraModel->name().c_str(), suffix.c_str()));
        if (smoothed->lights_with_filter_covariance > 0)
            report.addWarning(mrpt::format(
                "after smoothing, the least-squares covariance of %zu lights is not positive "
                "definite: map.txt keeps the filter's covariance of those; set "
                "min_cross_point_range to the camera's nearest reading range "
                "(doc/omni-fastslam.md)",
                smoothed->lights_with_filter_covariance));
    } else {
        core::saveFinalMap(best.map, out.path());
        drawBestParticle(scene);
    }
    const core::RunTimer checking;
    if (const auto check = smoother().cameraPoseCheck(best))
        reportSensorPoseChecks("omni-fastslam", "a landmark", "doc/multirobot.md",
                               {{"camera", *check, std::nullopt, {}}}, checking.elapsedSeconds(),
                               report, args.quiet);
    drawOdometryAndGroundTruth(scene, app.odometryPath, start.groundTruth);
    if (const auto& landmarks = trueLandmarks(start.groundTruthPrefix))
        drawLandmarks(scene, *landmarks);

    report.setCount("frames", steps);
    report.setCount("frames_with_images", framesWithImages);
    // the input the measurements came from, frame by frame (`input`)
    report.setCount("frames_with_bearings_used", framesWithBearingsUsed);
    report.setCount("images_searched", imagesSearched);
    report.setCount("measurements", measurements);
    size_t associated = 0;  // by the best particle, over its path
    for (const auto* s : best.path.stepsOldestFirst())
        associated += s->state.correspondences.size();
    report.setCount("associated_measurements", associated);
    // the shipped halls associate 90 %, MRCLAM (bearings only) 77-83 %
    if (2 * associated < measurements)
        report.addWarning(mrpt::format(
            "the best particle associated %zu of the %zu bearings with a light: the path is "
            "almost the odometry's; check %s, [LightDetector] and the camera pose on the "
            "robot (doc/omni-fastslam.md)",
            associated, measurements, cameraModel->name().c_str()));
    report.setCount("particles", filter().particlesCount());
    report.setCount("landmarks", (smoothed ? smoothed->map : best.map).landmarks().size());
    report.setCount("candidates", best.map.candidates().size());
    reportCameraModel(report);
    // which camera pose the measurement model used: the config's, or the observations' own
    const auto& pose = best.map.sensorPoseInUse();
    const bool configured = best.map.sensorOptions.sensor_in_robot.has_value();
    report.setResultJson("camera_pose_on_robot",
                         std::string("{\"source\": \"") + (configured ? "config" : "observations") +
                             "\", \"x_y_z_m_yaw_pitch_roll_deg\": " + poseJsonArray(pose) + "}");
    if (!args.quiet)
        std::printf("omni-fastslam: camera pose on the robot from the %s: %s\n",
                    configured ? "config (sensor_in_robot)" : "observations",
                    poseText(pose).c_str());
    // the field of view and reading range in use: each the config's, or the observations' own
    const auto limits = best.map.sensorLimitsInUse();
    std::string limitsJson, limitsLine;
    const auto addLimit = [&](const char* key, double value, bool set) {
        const char* source = set ? "config" : "observations";
        limitsJson += mrpt::format("%s\"%s\": {\"value\": %g, \"source\": \"%s\"}",
                                   limitsJson.empty() ? "{" : ", ", key, value, source);
        limitsLine +=
            mrpt::format("%s%s %g (%s)", limitsLine.empty() ? "" : ", ", key, value, source);
    };
    const auto& io = best.map.insertionOptions;
    addLimit("max_abs_azimuth_deg", mrpt::RAD2DEG(limits.max_abs_azimuth),
             best.map.sensorOptions.max_abs_azimuth.has_value());
    addLimit("min_cross_point_range", limits.min_range, io.min_cross_point_range.has_value());
    addLimit("max_cross_point_range", limits.max_range, io.max_cross_point_range.has_value());
    report.setResultJson("sensor_limits", limitsJson + "}");
    if (!args.quiet)
        std::printf(
            "omni-fastslam: camera's field of view and reading range [deg, m; 0: no limit]: %s\n",
            limitsLine.c_str());
    if (const auto associations = COmniFastSLAM::associationsOf(best);
        associations.labelled() > 0) {
        // evaluation only: the rawlog gave landmark numbers (landmarkID), the filter ignored them
        report.setResult("labelled_associations", associations.labelled());
        report.setResult("wrong_associations", associations.wrong());
        // per map landmark id: the landmark numbers of the measurements associated to it
        std::string table = "{";
        for (const auto& [landmark, ids] : associations.counts) {
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
}

std::optional<std::string> OmniFastSLAMApp::Impl::groundTruthName() const
{
    if (!start.groundTruth) return std::nullopt;
    return start.groundTruthPrefix;
}

}  // namespace mrpt_vslam::apps
