#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt_vslam/core/MetricsJson.h>
#include <mrpt_vslam/core/RunEvaluation.h>
#include <mrpt_vslam/core/UsageError.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace mrpt_vslam::core {

namespace {
TTrajectoryResult evaluatePath(const std::string& file, const TumTrajectory& ground_truth,
                               const std::string& ground_truth_file, const TEvalParams& params)
{
    TTrajectoryResult r;
    r.file = file;
    r.path = TumTrajectory::load(file);
    if (r.path.empty()) throw std::runtime_error(file + ": no poses");
    TTrajectoryMetricsOptions opts;
    opts.time_tolerance = params.time_tolerance;
    opts.heading_threshold = mrpt::DEG2RAD(params.heading_threshold_deg);
    opts.after = params.after;
    try {
        r.unaligned = evaluateTrajectory(r.path, ground_truth, opts);
        opts.align_se2 = true;
        r.aligned = evaluateTrajectory(r.path, ground_truth, opts);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(file + " against " + ground_truth_file + ": " + e.what());
    }
    return r;
}
}  // namespace

TEvalResult evaluateRun(const TEvalInputs& inputs, const TEvalParams& params)
{
    TEvalResult result;
    for (const auto& files : inputs.robots) {
        TRobotResult robot;
        robot.files = files;
        robot.ground_truth = TumTrajectory::loadGroundTruth(files.ground_truth);
        robot.estimate =
            evaluatePath(files.estimate, robot.ground_truth, files.ground_truth, params);
        if (!files.odometry.empty())
            robot.odometry =
                evaluatePath(files.odometry, robot.ground_truth, files.ground_truth, params);
        result.robots.push_back(std::move(robot));
    }
    if (!inputs.map_file.empty()) result.map = LandmarkFile::load(inputs.map_file);
    if (!inputs.landmarks_gt.empty())
        result.true_landmarks = LandmarkFile::loadTrueLandmarks(inputs.landmarks_gt);
    if (result.map && result.true_landmarks && !result.map->is_view_map)
        result.landmarks = evaluateLandmarks(
            result.map->landmarks, result.true_landmarks->landmarks, params.landmark_cutoff);
    return result;
}

TEvalResult evaluateRunFolder(const TEvalParams& params)
{
    if (!(params.landmark_cutoff > 0)) throw UsageError("--landmark-cutoff: must be > 0");
    if (!(params.time_tolerance >= 0)) throw UsageError("--time-tolerance: must be >= 0");
    if (std::isnan(params.after)) throw UsageError("--after: must be a time [s]");
    if (!(params.heading_threshold_deg > 0))
        throw UsageError("--heading-threshold-deg: must be > 0");
    const auto inputs = resolveInputs(params);
    auto result = evaluateRun(inputs, params);
    std::error_code ec;
    std::filesystem::create_directories(inputs.out_dir, ec);
    if (!std::filesystem::is_directory(inputs.out_dir))
        throw std::runtime_error(inputs.out_dir + ": cannot create output folder");
    writeMetricsJson(result, inputs, params,
                     (std::filesystem::path(inputs.out_dir) / "metrics.json").string());
    return result;
}

void printEvalSummary(std::ostream& os, const TEvalResult& result)
{
    const auto line = [&](const std::string& what, const TTrajectoryMetrics& m) {
        os << mrpt::format(
            "%-22s ATE RMSE %.3f m (max %.3f m), heading RMSE %.2f deg, %.0f%% of "
            "frames under the heading threshold\n",
            what.c_str(), m.ate_rmse, m.ate_max, mrpt::RAD2DEG(m.heading_rmse),
            100 * m.heading_share_under_threshold);
    };
    for (const auto& r : result.robots) {
        const std::string robot = r.files.robot.empty() ? "" : r.files.robot + " ";
        line(robot + "estimate:", r.estimate.unaligned);
        line(robot + "estimate aligned:", r.estimate.aligned);
        if (r.odometry) line(robot + "odometry:", r.odometry->unaligned);
    }
    if (const auto& l = result.landmarks)
        os << mrpt::format(
            "landmarks:             %zu true, %zu estimated: %zu matched, %zu "
            "false (%zu duplicated), %zu missed; error mean %.3f m, max %.3f m\n",
            l->num_true, l->num_estimated, l->num_matched, l->num_false, l->num_duplicates,
            l->num_missed, l->error_mean, l->error_max);
}

}  // namespace mrpt_vslam::core
