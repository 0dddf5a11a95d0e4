#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/system/filesystem.h>
#include <mrpt_vslam/apps/LiveView.h>
#include <mrpt_vslam/apps/ViewSLAMApp.h>
#include <mrpt_vslam/core/ActionFrameSource.h>
#include <mrpt_vslam/core/AtomicFile.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/ObservationSelector.h>
#include <mrpt_vslam/core/OutputDirectory.h>
#include <mrpt_vslam/core/ProgressReporter.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/RunEvaluation.h>
#include <mrpt_vslam/core/RunOutputs.h>
#include <mrpt_vslam/core/RunReport.h>
#include <mrpt_vslam/core/RunTimer.h>
#include <mrpt_vslam/core/SingleRobotStart.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/viewmap/COmniViewSLAM.h>

#include <cmath>
#include <cstdio>
#include <opencv2/core/version.hpp>
#include <optional>
#include <stdexcept>

namespace mrpt_vslam::apps {

using viewmap::COmniViewSLAM;
using viewmap::CViewMap;
using viewmap::TViewDecision;

namespace {
constexpr const char* kAppSection = "ViewSLAM";
/// Two-sided 95 % bounds of χ²₃ (the robot pose NEES of a consistent filter).
constexpr double kNeesLow = 0.2158, kNeesHigh = 9.3484;

mrpt::math::TPose3D to3D(const mrpt::math::TPose2D& p) { return {p.x, p.y, 0, p.phi, 0, 0}; }

/// Mean, and the root of the mean square, of a series.
struct TSeriesStats {
    double sum = 0, sum_sq = 0, max = 0;
    size_t n = 0;
    void add(double v)
    {
        sum += v;
        sum_sq += v * v;
        max = std::max(max, v);
        n++;
    }
    double mean() const { return n ? sum / double(n) : std::nan(""); }
    double rms() const { return n ? std::sqrt(sum_sq / double(n)) : std::nan(""); }
};
}  // namespace

struct ViewSLAMApp::Impl {
    core::AppArguments args;
    core::CheckedConfigFile cfg;
    std::string rawlog, imageLabel = "OMNICAM";
    uint32_t seed = 1;
    core::SingleRobotStart start;
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions motionModel;
    std::unique_ptr<COmniViewSLAM> slam;
    std::unique_ptr<LiveView> window;

    size_t frames = 0, framesWithImages = 0, attempted = 0, estimated = 0, accepted = 0;
    TSeriesStats sqrtTrace, nees, viewError;
    size_t neesInBounds = 0;

    void loadConfig();
    void draw(mrpt::opengl::COpenGLScene& scene, const core::TumTrajectory& path);
    void writeOutputs(ViewSLAMApp& app, const core::RunTimer& timer);
};

ViewSLAMApp::ViewSLAMApp(core::AppArguments args) : m_impl(std::make_unique<Impl>())
{
    m_impl->args = std::move(args);
}

ViewSLAMApp::~ViewSLAMApp() = default;

void ViewSLAMApp::Impl::loadConfig()
{
    cfg.loadFile(args.configFile, args.overrides);
    const std::string& name = cfg.name();
    const auto usage = [&](const std::string& what) {
        return core::UsageError(name + ": " + what);
    };

    rawlog = args.resolveRawlog(cfg, kAppSection);
    seed = args.resolveSeed(static_cast<uint32_t>(cfg.read_int(kAppSection, "random_seed", 0)));
    imageLabel = cfg.read_string(kAppSection, "image_label", imageLabel);
    start.loadFromConfig(cfg, kAppSection);

    try {
        slam = COmniViewSLAM::fromConfig(cfg, seed);
        motionModel = core::ActionFrameSource::loadMotionModel(cfg, "MotionModel");
    } catch (const core::UsageError& e) {
        throw usage(e.what());
    } catch (const std::exception& e) {
        throw usage(core::oneLineMessage(e));
    }
    cfg.throwIfUnreadKeys();
}

void ViewSLAMApp::initialize()
{
    auto& d = *m_impl;
    d.loadConfig();
    if (!mrpt::system::fileExists(d.rawlog))
        throw std::runtime_error(d.rawlog + ": cannot open rawlog");
    d.start.resolve(d.args, d.rawlog);
    outDir = d.args.outDir;
    if (d.args.gui) d.window = std::make_unique<LiveView>("view-slam");
}

void ViewSLAMApp::Impl::draw(mrpt::opengl::COpenGLScene& scene, const core::TumTrajectory& path)
{
    scene.insert(mrpt::opengl::CGridPlaneXY::Create(-5, 25, -5, 15, 0, 1));
    scene.insert(slam->map().getVisualization());
    scene.insert(core::trajectoryAsLines(path, {0, 0.8f, 0}, "estimate"));
}

void ViewSLAMApp::run()
{
    auto& d = *m_impl;
    core::OutputDirectory out(outDir);
    core::RunTimer timer;
    core::RawlogReader reader(d.rawlog);
    core::ProgressReporter progress("view-slam", 0, d.args.quiet);
    core::AtomicFile steps(out.file("steps.txt")), observations(out.file("observations.txt"));
    steps.stream()
        << "# view-slam: one line per frame. t [s]; x y [m] yaw [rad] of the EKF robot "
           "estimate; sqrt_trace_Pvv; nees of the robot pose (nan without ground "
           "truth); features; candidates; accepted observations; best inliers; views "
           "after the frame; new_view (1 if one was started); reason; sure_points "
           "(information policy); information_balance [nats]; step_ms\n"
           "# t x y yaw sqrt_trace_Pvv nees features candidates accepted "
           "best_inliers views new_view reason sure_points information_balance step_ms\n";
    observations.stream()
        << "# view-slam: one line per attempted view observation. frame; t [s]; view; "
           "matches; inliers; estimated (RANSAC found phi, beta); accepted (passed the gate); "
           "phi beta [rad]; sigma_phi sigma_beta [rad] (from R); nis\n"
           "# frame t view matches inliers estimated accepted phi beta sigma_phi sigma_beta "
           "nis\n";

    using core::ObservationSelector;
    core::ActionFrameSource source(
        reader, {ObservationSelector::of<mrpt::obs::CObservationImage>(d.imageLabel)},
        d.motionModel);
    mrpt::poses::CPose2D odometry(d.start.pose);
    bool started = false;
    mrpt::obs::CActionCollection::Ptr actions;
    mrpt::obs::CSensoryFrame::Ptr frame;
    char line[512];
    while (source.next(actions, frame)) {
        const auto image =
            ObservationSelector::firstIn<mrpt::obs::CObservationImage>(*frame, d.imageLabel);
        const auto move = actions->getBestMovementEstimation();
        const auto [Q, u] = move->poseChange->getCovarianceAndMean();
        const double t =
            mrpt::Clock::toDouble(image ? image->timestamp : actions->begin()->get()->timestamp);
        if (!started) {
            d.slam->reset(d.start.pose);
            started = true;
        }
        if (image) d.framesWithImages++;
        COmniViewSLAM::TStepResult r;
        timer.startStep();
        try {
            if (image) d.slam->useCameraPoseOf(image->cameraPose);
            r = d.slam->processStep(u.asTPose(), Q.asEigen(), image ? &image->image : nullptr, t,
                                    image && image->image.isExternallyStored()
                                        ? image->image.getExternalStorageFile()
                                        : std::string());
        } catch (const std::exception& e) {
            throw std::runtime_error(
                d.rawlog + ": frame " + std::to_string(d.frames) + ": " +
                (image && image->image.isExternallyStored()
                     ? "image '" + image->image.getExternalStorageFileAbsolutePath() + "': "
                     : std::string()) +
                core::oneLineMessage(e));
        }
        const double ms = timer.endStep();
        if (image) image->image.unload();

        const auto& ekf = d.slam->ekf();
        const auto x = ekf.robotPose();
        estimatedPath.push_back(t, to3D(x));
        odometry = odometry + u;
        odometryPath.push_back(t, to3D(odometry.asTPose()));
        const double sqrtTrace = std::sqrt(ekf.robotCovariance().trace());
        d.sqrtTrace.add(sqrtTrace);
        double nees = std::nan("");
        if (d.start.groundTruth) {
            const int k = d.start.groundTruth->nearestIndex(t, 0.05);
            if (k >= 0) {
                const auto& g = d.start.groundTruth->poses[size_t(k)];
                nees = ekf.robotNEES({g.x, g.y, g.yaw});
                d.nees.add(nees);
                if (nees >= kNeesLow && nees <= kNeesHigh) d.neesInBounds++;
            }
        }
        size_t bestInliers = 0;
        for (const auto& o : r.observations) {
            d.attempted++;
            d.estimated += o.estimated;
            d.accepted += o.accepted;
            if (o.accepted) bestInliers = std::max(bestInliers, o.inliers);
            std::snprintf(line, sizeof(line),
                          "%zu %.6f %zu %zu %zu %d %d %.6f %.6f %.6g %.6g %.4g\n", d.frames, t,
                          o.view, o.matches, o.inliers, int(o.estimated), int(o.accepted), o.z.phi,
                          o.z.beta, std::sqrt(o.R(0, 0)), std::sqrt(o.R(1, 1)), o.nis);
            observations.stream() << line;
        }
        std::snprintf(line, sizeof(line),
                      "%.6f %.6f %.6f %.6f %.6g %.6g %zu %zu %zu %zu %zu %d %s %.4g %.4g %.3f\n", t,
                      x.x, x.y, x.phi, sqrtTrace, nees, r.features, r.observations.size(),
                      r.accepted(), bestInliers, ekf.viewCount(), int(r.new_view.has_value()),
                      TViewDecision::reasonName(r.decision.reason), r.decision.sure_points,
                      r.decision.information_balance, ms);
        steps.stream() << line;
        progress.update(++d.frames);
        if (d.window) d.window->show([&](auto& scene) { d.draw(scene, estimatedPath); });
    }
    progress.finish(d.frames);
    if (d.framesWithImages == 0)
        throw std::runtime_error(d.rawlog + ": no frames with odometry and a " + d.imageLabel +
                                 " image (action / sensory-frame pairs, or CObservationOdometry "
                                 "with CObservationImage); the rawlog has: " +
                                 reader.summary().describe());
    steps.commit();
    observations.commit();
    d.writeOutputs(*this, timer);
    if (d.window && !d.args.quiet) d.window->waitUntilClosed();
}

void ViewSLAMApp::Impl::writeOutputs(ViewSLAMApp& app, const core::RunTimer& timer)
{
    core::OutputDirectory out(app.outDir);
    const CViewMap& map = slam->map();
    app.estimatedPath.save(out.file("estimated_path.tum"), "view-slam: EKF robot estimate");
    app.odometryPath.save(out.file("odometry_path.tum"), "view-slam: dead reckoning");
    core::saveFinalMap(map, app.outDir);

    // View position errors against the true pose at each view's image (no alignment: the
    // filter starts from the true pose).
    if (start.groundTruth) {
        for (const auto& v : map.views()) {
            const int k = start.groundTruth->nearestIndex(v.timestamp, 0.05);
            if (k < 0) continue;
            const auto& g = start.groundTruth->poses[size_t(k)];
            viewError.add(std::hypot(v.pose.x - g.x, v.pose.y - g.y));
        }
    }

    mrpt::opengl::COpenGLScene scene;
    draw(scene, app.estimatedPath);
    scene.insert(core::trajectoryAsLines(app.odometryPath, {0.9f, 0.1f, 0.1f}, "odometry"));
    if (start.groundTruth)
        scene.insert(core::trajectoryAsLines(*start.groundTruth, {0, 0, 0}, "ground truth"));
    core::saveScene(scene, out.file("final.3Dscene"));

    cfg.writeEffectiveConfig(out.file("config.ini"));
    core::RunReport report("view-slam");
    args.describeInputs(report, cfg.effectiveText(), rawlog, seed);
    report.setOpenCvVersion(CV_VERSION);
    report.setCount("frames", frames);
    report.setCount("frames_with_images", framesWithImages);
    report.setCount("views", map.size());
    report.setCount("observations_attempted", attempted);
    report.setCount("observations_estimated", estimated);
    report.setCount("observations_accepted", accepted);
    report.setTiming(timer);
    // which camera orientation the front-end used: the config's, or the images' own
    const mrpt::poses::CPose3D rotation(
        mrpt::math::CMatrixDouble33(slam->extractor().cameraToRobot()), mrpt::math::TPoint3D());
    const char* source = slam->cameraOnRobotConfigured() ? "config" : "observations";
    report.setResultJson(
        "camera_orientation_on_robot",
        mrpt::format("{\"source\": \"%s\", \"yaw_pitch_roll_deg\": [%g, %g, %g]}", source,
                     mrpt::RAD2DEG(rotation.yaw()), mrpt::RAD2DEG(rotation.pitch()),
                     mrpt::RAD2DEG(rotation.roll())));
    if (!args.quiet)
        std::printf(
            "view-slam: camera orientation on the robot from the %s: yaw %g, pitch %g, "
            "roll %g deg\n",
            slam->cameraOnRobotConfigured() ? "config ([CameraOnRobot])" : source,
            mrpt::RAD2DEG(rotation.yaw()), mrpt::RAD2DEG(rotation.pitch()),
            mrpt::RAD2DEG(rotation.roll()));
    report.setResult("mean_sqrt_trace_Pvv", sqrtTrace.mean());
    report.setResult("final_sqrt_trace_Pvv", std::sqrt(slam->ekf().robotCovariance().trace()));
    if (start.groundTruth) {
        report.setGroundTruth(start.groundTruthPrefix);
        report.setResult("nees_mean", nees.mean());
        report.setResult("nees_in_95_bounds",
                         nees.n ? double(neesInBounds) / double(nees.n) : std::nan(""));
        report.setResult("view_position_rmse", viewError.rms());
        report.setResult("view_position_max", viewError.n ? viewError.max : std::nan(""));
    }
    report.write(out.file("run.json"));

    if (start.groundTruth) {
        core::TEvalParams eval;
        eval.run_dir = app.outDir;
        eval.ground_truth = start.groundTruthPrefix;
        core::evaluateRunFolder(eval);
    }
}

}  // namespace mrpt_vslam::apps
