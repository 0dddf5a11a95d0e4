#include "EvalApp.h"

#include <mrpt/core/bits_math.h>

#include <filesystem>
#include <stdexcept>

#include "MetricsJson.h"
#include "Plots.h"

namespace mrpt_vslam::eval {
namespace fs = std::filesystem;

TTrajectoryResult EvalApp::evaluatePath(const std::string& file,
                                        const core::TumTrajectory& ground_truth) const {
    TTrajectoryResult r;
    r.file = file;
    r.path = core::TumTrajectory::load(file);
    if (r.path.empty()) throw std::runtime_error(file + ": no poses");
    core::TTrajectoryMetricsOptions opts;
    opts.time_tolerance = params.time_tolerance;
    opts.heading_threshold = mrpt::DEG2RAD(params.heading_threshold_deg);
    try {
        r.unaligned = core::evaluateTrajectory(r.path, ground_truth, opts);
        opts.align_se2 = true;
        r.aligned = core::evaluateTrajectory(r.path, ground_truth, opts);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(file + ": " + e.what());
    }
    return r;
}

void EvalApp::evaluate(const TEvalInputs& inputs) {
    result = {};
    for (const auto& files : inputs.robots) {
        TRobotResult robot;
        robot.files = files;
        robot.ground_truth = core::TumTrajectory::load(files.ground_truth);
        if (robot.ground_truth.empty()) throw std::runtime_error(files.ground_truth + ": no poses");
        robot.estimate = evaluatePath(files.estimate, robot.ground_truth);
        if (!files.odometry.empty())
            robot.odometry = evaluatePath(files.odometry, robot.ground_truth);
        result.robots.push_back(std::move(robot));
    }
    if (!inputs.map_file.empty()) result.map = core::LandmarkFile::load(inputs.map_file);
    if (!inputs.landmarks_gt.empty())
        result.true_landmarks = core::LandmarkFile::load(inputs.landmarks_gt);
    if (result.map && result.true_landmarks && !result.map->is_view_map)
        result.landmarks = core::evaluateLandmarks(
            result.map->landmarks, result.true_landmarks->landmarks, params.landmark_cutoff);
}

void EvalApp::run() {
    if (!(params.landmark_cutoff > 0)) throw std::runtime_error("--landmark-cutoff: must be > 0");
    if (!(params.time_tolerance >= 0)) throw std::runtime_error("--time-tolerance: must be >= 0");
    if (!(params.heading_threshold_deg > 0))
        throw std::runtime_error("--heading-threshold-deg: must be > 0");
    const auto inputs = resolveInputs(params);
    evaluate(inputs);
    std::error_code ec;
    fs::create_directories(inputs.out_dir, ec);
    if (!fs::is_directory(inputs.out_dir))
        throw std::runtime_error(inputs.out_dir + ": cannot create output folder");
    const fs::path out(inputs.out_dir);
    writeMetricsJson(result, inputs, params, (out / "metrics.json").string());
    plotPaths(result, params.align, (out / "paths.png").string());
    plotErrors(result, params.align, (out / "errors.png").string());
    if (result.landmarks)
        plotLandmarkErrors(*result.landmarks, (out / "landmark_errors.png").string());
}

}  // namespace mrpt_vslam::eval
