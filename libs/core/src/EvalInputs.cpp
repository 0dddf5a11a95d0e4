#include <mrpt/system/string_utils.h>
#include <mrpt_vslam/core/EndsWith.h>
#include <mrpt_vslam/core/EvalInputs.h>
#include <mrpt_vslam/core/UsageError.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace mrpt_vslam::core {
namespace fs = std::filesystem;
namespace {

/** RUN_DIR/run.json, null when there is none. Throws for one that is not JSON or that says the
 *  run did not complete: a failed run's folder holds no result to evaluate. */
nlohmann::json runReportOf(const std::string& run_dir)
{
    const auto runJson = (fs::path(run_dir) / "run.json").string();
    if (!fs::exists(runJson)) return {};
    std::ifstream in(runJson);
    nlohmann::json j;
    try {
        in >> j;
    } catch (const nlohmann::json::exception& e) {
        throw std::runtime_error(runJson + ": invalid JSON: " + e.what());
    }
    if (j.contains("completed") && j["completed"] == false)
        throw std::runtime_error(runJson + ": the run did not complete" +
                                 (j.contains("error") && j["error"].is_string()
                                      ? " (" + j["error"].get<std::string>() + ")"
                                      : std::string()) +
                                 ": nothing to evaluate");
    return j;
}

/// `--ground-truth` from the parameters, else from the run's report `j`; "" when neither has it.
std::string groundTruthArgument(const TEvalParams& p, const nlohmann::json& j)
{
    if (!p.ground_truth.empty() || p.run_dir.empty()) return p.ground_truth;
    const auto runJson = (fs::path(p.run_dir) / "run.json").string();
    if (!j.contains("ground_truth") || j["ground_truth"].is_null()) return {};
    if (!j["ground_truth"].is_string())
        throw std::runtime_error(runJson + ": key \"ground_truth\" must be a string");
    std::string gt = j["ground_truth"].get<std::string>();
    // A relative path is taken from the current folder, else from the run folder.
    const auto inRun = fs::path(p.run_dir) / gt;
    if (fs::path(gt).is_relative() && !fs::exists(gt) && !fs::exists(gt + ".groundtruth.tum") &&
        (fs::exists(inRun) || fs::exists(inRun.string() + ".groundtruth.tum")))
        gt = inRun.string();
    return gt;
}

/// Robots of a run folder: "" for estimated_path.tum, R for estimated_path_R.tum (sorted).
std::vector<TRobotFiles> robotsInRunDir(const std::string& run_dir)
{
    if (!fs::is_directory(run_dir)) throw std::runtime_error(run_dir + ": not a folder");
    const std::string stem = "estimated_path", ext = ".tum";
    std::vector<TRobotFiles> robots;
    for (const auto& entry : fs::directory_iterator(run_dir)) {
        const auto name = entry.path().filename().string();
        if (name.rfind(stem, 0) != 0 || !endsWith(name, ext)) continue;
        // What lies between the stem and the extension: "" or "_<ROBOT>".
        const auto middle = name.substr(stem.size(), name.size() - stem.size() - ext.size());
        if (!middle.empty() && (middle.size() < 2 || middle[0] != '_')) continue;
        TRobotFiles r;
        r.robot = middle.empty() ? std::string() : middle.substr(1);
        r.estimate = entry.path().string();
        const auto odo =
            fs::path(run_dir) /
            (r.robot.empty() ? "odometry_path.tum" : "odometry_path_" + r.robot + ".tum");
        if (fs::exists(odo)) r.odometry = odo.string();
        robots.push_back(r);
    }
    if (robots.empty())
        throw std::runtime_error(run_dir + ": no estimated_path.tum or estimated_path_<ROBOT>.tum");
    std::sort(robots.begin(), robots.end(),
              [](const auto& a, const auto& b) { return a.robot < b.robot; });
    return robots;
}

}  // namespace

std::string groundTruthPrefixOf(const std::string& name)
{
    for (const std::string ext : {".rawlog.gz", ".rawlog", ".groundtruth.tum"})
        if (name.size() > ext.size() &&
            mrpt::system::strCmpI(name.substr(name.size() - ext.size()), ext))
            return name.substr(0, name.size() - ext.size());
    return name;
}

std::string groundTruthFileOf(const std::string& prefix, const std::string& robot, bool only_robot)
{
    const std::string single = prefix + ".groundtruth.tum";
    if (robot.empty()) return single;
    const std::string own = prefix + ".groundtruth_" + robot + ".tum";
    return only_robot && !fs::exists(own) && fs::exists(single) ? single : own;
}

TEvalInputs resolveInputs(const TEvalParams& p)
{
    TEvalInputs in;
    if (!p.estimate_file.empty()) {
        in.robots.push_back({"", p.estimate_file, p.odometry_file, ""});
    } else {
        if (p.run_dir.empty())
            throw UsageError("give RUN_DIR or --estimate FILE (see vslam-eval --help)");
        in.robots = robotsInRunDir(p.run_dir);
    }
    const auto gtArg =
        groundTruthArgument(p, p.run_dir.empty() ? nlohmann::json() : runReportOf(p.run_dir));
    if (gtArg.empty())
        throw std::runtime_error((p.run_dir.empty() ? p.estimate_file : p.run_dir) +
                                 ": no ground truth: pass --ground-truth or set \"ground_truth\" "
                                 "in run.json");
    // NAME.groundtruth.tum names its prefix NAME too (its landmarks, the other robots' files)
    const auto prefix = groundTruthPrefixOf(gtArg);
    const bool file = endsWith(gtArg, ".tum"), named = prefix != gtArg;
    if (file && in.robots.size() == 1) {
        in.robots[0].ground_truth = gtArg;
    } else if (file && !named) {
        throw std::runtime_error(gtArg + ": one ground-truth file for " +
                                 std::to_string(in.robots.size()) +
                                 " robots; pass the prefix NAME instead");
    } else {
        for (auto& r : in.robots)
            r.ground_truth = groundTruthFileOf(prefix, r.robot, in.robots.size() == 1);
    }
    if ((!file || named) && p.landmarks_gt.empty() && fs::exists(prefix + ".landmarks.txt"))
        in.landmarks_gt = prefix + ".landmarks.txt";
    if (!p.landmarks_gt.empty()) in.landmarks_gt = p.landmarks_gt;
    in.map_file = p.map_file;
    if (in.map_file.empty() && !p.run_dir.empty() && p.estimate_file.empty() &&
        fs::exists(fs::path(p.run_dir) / "map.txt"))
        in.map_file = (fs::path(p.run_dir) / "map.txt").string();
    in.out_dir = !p.out_dir.empty() ? p.out_dir : p.run_dir;
    if (in.out_dir.empty())
        throw UsageError("--out DIR is required with --estimate (see vslam-eval --help)");
    return in;
}

}  // namespace mrpt_vslam::core
