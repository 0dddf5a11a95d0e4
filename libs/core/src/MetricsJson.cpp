#include <mrpt/core/bits_math.h>
#include <mrpt_vslam/core/AtomicFile.h>
#include <mrpt_vslam/core/MetricsJson.h>
#include <mrpt_vslam/core/Version.h>

#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>

namespace mrpt_vslam::core {
namespace {

using nlohmann::json;

/// A number, or null when it is not finite (no frame or landmark to average over).
json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json errorSummary(const TTrajectoryMetrics& m)
{
    return {{"matched_poses", m.matchedPoses()},
            {"ate_rmse_m", num(m.ate_rmse)},
            {"ate_mean_m", num(m.ate_mean)},
            {"ate_max_m", num(m.ate_max)},
            {"heading_rmse_deg", num(mrpt::RAD2DEG(m.heading_rmse))},
            {"heading_mean_deg", num(mrpt::RAD2DEG(m.heading_mean))},
            {"heading_max_deg", num(mrpt::RAD2DEG(m.heading_max))},
            {"heading_share_under_threshold", num(m.heading_share_under_threshold)}};
}

json trajectoryBlock(const TTrajectoryResult& r)
{
    json j = errorSummary(r.unaligned);
    j["file"] = r.file;
    j["poses"] = r.unaligned.estimate_poses;
    json aligned = errorSummary(r.aligned);
    aligned["alignment"] = {{"x_m", r.aligned.alignment.x},
                            {"y_m", r.aligned.alignment.y},
                            {"yaw_deg", mrpt::RAD2DEG(r.aligned.alignment.phi)}};
    j["aligned_se2"] = aligned;
    return j;
}

json robotBlock(const TRobotResult& r)
{
    json j = {{"ground_truth_file", r.files.ground_truth},
              {"ground_truth_poses", r.ground_truth.size()},
              {"estimate", trajectoryBlock(r.estimate)}};
    j["odometry"] = r.odometry ? trajectoryBlock(*r.odometry) : json(nullptr);
    return j;
}

json landmarkBlock(const TLandmarkMetrics& m, const std::string& truth_file)
{
    json table = json::array();
    for (const auto& t : m.matches) {
        json row = {{"true_id", t.true_id},
                    {"x", num(t.true_position.x)},
                    {"y", num(t.true_position.y)},
                    {"z", num(t.true_position.z)}};
        if (t.matched()) {
            row.update({{"est_id", t.est_id},
                        {"ex", num(t.est_position.x)},
                        {"ey", num(t.est_position.y)},
                        {"ez", num(t.est_position.z)},
                        {"error", t.error_norm}});
        } else {
            row.update({{"est_id", nullptr},
                        {"ex", nullptr},
                        {"ey", nullptr},
                        {"ez", nullptr},
                        {"error", nullptr}});
        }
        table.push_back(row);
    }
    return {{"ground_truth_file", truth_file},
            {"cutoff_m", m.cutoff},
            {"true_landmarks", m.num_true},
            {"estimated_landmarks", m.num_estimated},
            {"matched", m.num_matched},
            {"missed", m.num_missed},
            {"false", m.num_false},
            {"duplicated", m.num_duplicates},
            {"error_mean_m", num(m.error_mean)},
            {"error_rmse_m", num(m.error_rmse)},
            {"error_max_m", num(m.error_max)},
            {"false_ids", m.false_ids},
            {"duplicate_ids", m.duplicate_ids},
            {"table", table}};
}

}  // namespace

void writeMetricsJson(const TEvalResult& result, const TEvalInputs& inputs,
                      const TEvalParams& params, const std::string& file)
{
    json j = {{"generator", "vslam-eval"},
              {"versions", {{"mrpt_vslam", projectVersion()}, {"mrpt", mrptVersion()}}},
              {"options",
               {{"time_tolerance_s", params.time_tolerance},
                {"heading_threshold_deg", params.heading_threshold_deg},
                {"landmark_cutoff_m", params.landmark_cutoff}}}};
    if (std::isfinite(params.after)) j["options"]["after_s"] = params.after;
    if (result.robots.size() == 1 && result.robots[0].files.robot.empty()) {
        j.update(robotBlock(result.robots[0]));
    } else {
        json robots = json::object();
        for (const auto& r : result.robots) robots[r.files.robot] = robotBlock(r);
        j["robots"] = robots;
    }
    if (result.map) {
        j["map"] = {{"file", inputs.map_file},
                    {"kind", result.map->is_view_map ? "views" : "landmarks"},
                    {"elements", result.map->size()}};
    } else {
        j["map"] = nullptr;
    }
    if (result.landmarks) {
        j["landmarks"] = landmarkBlock(*result.landmarks, inputs.landmarks_gt);
    } else {
        j["landmarks"] = nullptr;
    }
    AtomicFile out(file);
    out.stream() << std::setw(2) << j << "\n";
    out.commit();
}

}  // namespace mrpt_vslam::core
