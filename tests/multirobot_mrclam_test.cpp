// multirobot-vslam on real data: UTIAS MRCLAM dataset 7, robots 1-3. The first 300 s are shipped
// (datasets/utias-mrclam, identities hidden and kept, the robots' readings of each other kept);
// the OnFullDataset tests need the full dataset (MRPT_VSLAM_MRCLAM_DIR, doc/real-data.md) and
// skip without it. All through mrclam.ini, with one filter of M = 500 but in the last test.
// Measured on the window with seeds 1-3, as shipped: R1 0.27-0.38 m, R2 0.17-0.29 m, R3
// 0.19-0.25 m against odometry 1.60 / 0.28 / 0.76 m. Over this window per-robot resampling alone
// keeps R1 (0.29-0.36 m team mean without the readings of robots), so their effect is checked
// without it: team mean 0.22 m with them, 0.66 m without.
#include <gtest/gtest.h>
#include <mrpt_vslam/core/RunEvaluation.h>
#include <mrpt_vslam/test/ExternalData.h>
#include <mrpt_vslam/test/RunCommand.h>
#include <mrpt_vslam/test/RunFiles.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

using mrpt_vslam::test::ScratchFolder;
using mrpt_vslam::test::TCommandResult;

namespace {
/// The shipped window: robots 1-3, the first 300 s (datasets/utias-mrclam/README.md).
const std::string kWindow = MRPT_VSLAM_SOURCE_DIR "/datasets/utias-mrclam/mrclam7-r123-0-300";

/// Robots 1-3 of the full dataset in `dataset` in a time window (mrclam2rawlog's --start and
/// --end; empty: the whole dataset) imported with the robots' readings of each other into
/// `<scratch>/window.rawlog`.
std::string importWindow(const ScratchFolder& scratch, const std::string& dataset,
                         const std::string& window)
{
    const std::string rawlog = scratch.file("window.rawlog");
    const TCommandResult import = mrpt_vslam::test::runCommand(
        std::string(MRPT_VSLAM_BIN_DIR "/mrclam2rawlog '") + dataset + "' --robots 1,2,3 " +
            window + " --command-delay 0.2 --keep-robot-measurements -q --out '" + rawlog + "'",
        scratch.path() / "import.log");
    EXPECT_EQ(import.exit_code, 0) << import.out;
    return rawlog;
}

/// A run of mrclam.ini (plus `options`) into `<scratch>/<name>`.
std::string runShipped(const ScratchFolder& scratch, const std::string& rawlog,
                       const std::string& name, const std::string& options)
{
    const std::string out = scratch.file(name);
    const TCommandResult r = mrpt_vslam::test::runCommand(
        std::string(MRPT_VSLAM_BIN_DIR "/multirobot-vslam " MRPT_VSLAM_SOURCE_DIR
                                       "/share/mrpt-vslam/config/multirobot-vslam/mrclam.ini '") +
            rawlog + "' -q --out '" + out + "' " + options,
        scratch.path() / (name + ".log"));
    EXPECT_EQ(r.exit_code, 0) << r.out;
    return out;
}

/// One filter of mrclam.ini with M = 500 (plus `options`) into `<scratch>/<name>`.
std::string runMrclam(const ScratchFolder& scratch, const std::string& rawlog,
                      const std::string& name, const std::string& options)
{
    return runShipped(
        scratch, rawlog, name,
        "--set ParticleFilter.sampleSize=500 --set MultiRobotVSLAM.filter_runs=1 " + options);
}

/// vslam-eval's evaluation of a run folder, in-process: the output map matched one-to-one to the
/// true landmarks within 0.5 m, and the path errors.
mrpt_vslam::core::TEvalParams evalParamsOf(const std::string& out)
{
    mrpt_vslam::core::TEvalParams params;
    params.run_dir = out;
    params.landmark_cutoff = 0.5;
    return params;
}

mrpt_vslam::core::TEvalResult evaluate(const std::string& out)
{
    const auto params = evalParamsOf(out);
    return mrpt_vslam::core::evaluateRun(mrpt_vslam::core::resolveInputs(params), params);
}

/// Team mean of the estimate's and of the odometry's position RMSE of a run folder.
std::pair<double, double> teamMeans(const std::string& out)
{
    const auto metrics = mrpt_vslam::test::readJson(out + "/metrics.json");
    double est = 0, odo = 0;
    for (const char* name : {"R1", "R2", "R3"}) {
        est += metrics["robots"][name]["estimate"]["ate_rmse_m"].get<double>() / 3;
        odo += metrics["robots"][name]["odometry"]["ate_rmse_m"].get<double>() / 3;
    }
    return {est, odo};
}
}  // namespace

TEST(MultiRobotVSLAMOnMrclam, RobotReadingsKeepTheTeamFarBelowOdometry)
{
    ScratchFolder scratch("mrclam-team");
    const std::string rawlog = kWindow + ".rawlog";
    // the particle's own map: map_along_path is checked below
    const auto runFilter = [&](const std::string& name, const std::string& options) {
        return runMrclam(scratch, rawlog, name,
                         "--seed 1 --set TeamPathSmoother.map_along_path=false "
                         "--set TeamPathSmoother.smooth_paths=false " +
                             options);
    };
    const std::string shipped = runFilter("shipped", "");
    const std::string noRpr = "--set MultiRobotVSLAM.resample_per_robot=false ";
    const std::string with = runFilter("with", noRpr);
    const std::string without =
        runFilter("without", noRpr + "--set MultiRobotVSLAM.robot_reading_ids=");

    const auto metrics = mrpt_vslam::test::readJson(shipped + "/metrics.json");
    for (const char* name : {"R1", "R3"})
        EXPECT_LT(metrics["robots"][name]["estimate"]["ate_rmse_m"].get<double>(),
                  0.5 * metrics["robots"][name]["odometry"]["ate_rmse_m"].get<double>())
            << name;
    const auto [est, odo] = teamMeans(shipped);
    EXPECT_LT(est, 0.4 * odo);
    // the readings of robots keep R1, which reads no landmark from 25 s to 50 s
    EXPECT_LT(teamMeans(with).first, 0.6 * teamMeans(without).first);

    const auto run = mrpt_vslam::test::readJson(shipped + "/run.json");
    EXPECT_EQ(run["counts"]["robot_readings"].get<int>(),
              300);  // R1-R3 reading each other in 300 s
    EXPECT_EQ(
        mrpt_vslam::test::readJson(without + "/run.json")["counts"]["robot_readings"].get<int>(),
        0);
    // every true landmark the robots saw is in the particle's map (within 0.5 m), identities
    // unread
    EXPECT_GE(run["results"]["landmark_merging"]["true_landmarks_mapped"].get<int>(), 10);
    EXPECT_FALSE(run["results"].contains("association_by_identity"));
}

TEST(MultiRobotVSLAMOnMrclam, KnownCorrespondencesMapEachLandmarkOnce)
{
    // associate_by_identity on the rawlog with identities (the hidden one's ground truth): one
    // landmark per identity, every fused reading of its own identity, each landmark within
    // 0.5 m of its post. Measured with seeds 1-3: all 15 identities, 3549 readings fused, team
    // mean 0.19-0.25 m against odometry 0.88 m
    ScratchFolder scratch("mrclam-identities");
    const std::string out =
        runMrclam(scratch, kWindow + "-ids.rawlog", "run",
                  "--ground-truth '" + kWindow +
                      "' --seed 1 --set MappingApplication_visualLandmarksMap_00_insertOpts."
                      "associate_by_identity=true --set TeamPathSmoother.map_along_path=false "
                      "--set TeamPathSmoother.smooth_paths=false");
    const auto run = mrpt_vslam::test::readJson(out + "/run.json");
    const auto& ids = run["results"]["association_by_identity"];
    EXPECT_EQ(ids["identities"].get<int>(), 15);
    EXPECT_EQ(ids["identities_with_several_landmarks"].get<int>(), 0);
    EXPECT_EQ(ids["landmarks_with_identity"].get<int>(), ids["identities"].get<int>());
    EXPECT_GT(ids["fused_measurements"].get<int>(), 3000);
    EXPECT_EQ(ids["fused_with_another_identity"].get<int>(), 0);
    const auto& merging = run["results"]["landmark_merging"];
    EXPECT_EQ(merging["map_landmarks"].get<int>(), ids["identities"].get<int>());
    EXPECT_EQ(merging["map_landmarks_without_true_landmark"].get<int>(), 0);
    const auto [est, odo] = teamMeans(out);
    EXPECT_LT(est, 0.4 * odo);
}

TEST(MultiRobotVSLAMOnMrclam, SmoothedPathsAndTheMapAlongThemMeetTheTargets)
{
    // identities hidden, as shipped (map along the path, smoothed paths; the count threshold
    // relative to the 300 s window: 49 readings of 2004 frames, where posts get 120-370, a
    // third of the whole dataset's). Measured with seeds 1-2: every robot 0.09-0.12 m smoothed
    // against 0.17-0.38 m for the best particle's path; 15 landmarks, all 15 posts matched
    // one-to-one within 0.5 m, where the particle's own map holds 27-36; distance scales 0.87-0.92.
    ScratchFolder scratch("mrclam-smoothed");
    const std::string rawlog = kWindow + ".rawlog";
    const std::string& prefix = kWindow;
    for (const std::string seed : {"1", "2"}) {
        const std::string out = runMrclam(scratch, rawlog, "run" + seed, "--seed " + seed);
        const auto result = evaluate(out);
        ASSERT_TRUE(result.landmarks.has_value());
        EXPECT_EQ(result.landmarks->num_matched, 15u) << "seed " << seed;
        EXPECT_LE(result.landmarks->num_estimated, 17u) << "seed " << seed;
        const auto run = mrpt_vslam::test::readJson(out + "/run.json");
        EXPECT_GT(run["counts"]["particle_map_landmarks"].get<size_t>(),
                  result.landmarks->num_estimated + 8)
            << "seed " << seed;
        EXPECT_TRUE(std::filesystem::exists(out + "/particle_map.txt"));

        ASSERT_EQ(result.robots.size(), 3u);
        for (const auto& robot : result.robots) {
            const std::string& r = robot.files.robot;
            mrpt_vslam::core::TEvalInputs filter;
            filter.robots.push_back(
                {r, out + "/filter_path_" + r + ".tum", "", prefix + ".groundtruth_" + r + ".tum"});
            const double filtered = mrpt_vslam::core::evaluateRun(filter, evalParamsOf(out))
                                        .robots.at(0)
                                        .estimate.unaligned.ate_rmse;
            const double smoothed = robot.estimate.unaligned.ate_rmse;
            EXPECT_LT(smoothed, 0.15) << r << " seed " << seed;
            EXPECT_LT(smoothed, 0.75 * filtered) << r << " seed " << seed;
            const double distance = run["results"]["smoothing_odometry_scales"][r][0].get<double>();
            EXPECT_GT(distance, 0.8) << r;
            EXPECT_LT(distance, 0.97) << r;  // the commands overstate distances
        }
    }
}

TEST(MultiRobotVSLAMOnFullDataset, ReanchoringBringsARobotBackAfterAGap)
{
    const auto dataset7 = mrpt_vslam::test::mrclamDataset7();
    if (!dataset7.missing.empty()) GTEST_SKIP() << dataset7.missing;
    // 450-720 s: R2 reads no post for 48 s (537-585 s); on some seeds the best particle comes
    // back displaced and its readings go to wrong posts. Which seeds is chaotic (a start moved by
    // millimetres changes them), so the test counts over six. Measured: R2 under 0.3 m smoothed
    // on 5-6 of 6 seeds with reanchoring, 2 of 6 without (0.43-1.26 m on the others); the mean
    // with reanchoring 0.44-0.64 of that without.
    ScratchFolder scratch("mrclam-reanchored");
    const std::string rawlog = importWindow(scratch, dataset7.path, "--start 450 --end 720");
    std::map<std::string, std::vector<double>> r2;  // per reanchor_gap, per seed
    for (const std::string seed : {"1", "2", "3", "4", "5", "6"}) {
        for (const std::string gap : {"0", "10"}) {
            const std::string out =
                runMrclam(scratch, rawlog, "run" + seed + "-" + gap,
                          "--seed " + seed + " --set TeamPathSmoother.reanchor_gap=" + gap);
            const auto result = evaluate(out);
            for (const auto& robot : result.robots)
                if (robot.files.robot == "R2") r2[gap].push_back(robot.estimate.unaligned.ate_rmse);
            ASSERT_EQ(r2[gap].size(), std::stoul(seed));
            const auto run = mrpt_vslam::test::readJson(out + "/run.json");
            ASSERT_TRUE(result.landmarks.has_value());
            if (gap == "0") {
                EXPECT_EQ(run["counts"]["smoothing_reanchored"].get<size_t>(), 0u) << seed;
            } else {
                EXPECT_EQ(result.landmarks->num_matched, 15u) << "seed " << seed;
            }
            std::printf("seed %s, reanchor_gap %s: R2 %.3f m, %zu landmarks\n", seed.c_str(),
                        gap.c_str(), r2[gap].back(), result.landmarks->num_estimated);
        }
        // reanchoring makes no seed's R2 worse
        EXPECT_LT(r2["10"].back(), r2["0"].back() + 0.02) << "seed " << seed;
    }
    const auto under = [](const std::vector<double>& v) {
        return std::count_if(v.begin(), v.end(), [](double e) { return e < 0.3; });
    };
    const auto mean = [](const std::vector<double>& v) {
        return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
    };
    EXPECT_GE(under(r2["10"]), 5);
    EXPECT_LE(under(r2["0"]), 3);
    EXPECT_LT(mean(r2["10"]), 0.7 * mean(r2["0"]));
}

TEST(MultiRobotVSLAMOnFullDataset, IndependentRunsKeepTheTeam)
{
    const auto dataset7 = mrpt_vslam::test::mrclamDataset7();
    if (!dataset7.missing.empty()) GTEST_SKIP() << dataset7.missing;
    // The whole dataset, as shipped (M = 2000, three filters, the least smoothed cost kept) from
    // seed 4, whose filter alone loses the whole team (0.45-0.52 m, 22 landmarks, cost 13783
    // against 11760-12000 of the runs that keep it). Measured: seed 5's run kept, every robot
    // 0.10-0.12 m, the 15 posts mapped once.
    ScratchFolder scratch("mrclam-filter-runs");
    const std::string rawlog = importWindow(scratch, dataset7.path, "");
    const std::string out = runShipped(scratch, rawlog, "run", "--seed 4");
    const auto run = mrpt_vslam::test::readJson(out + "/run.json");
    const auto& runs = run["results"]["filter_runs"];
    ASSERT_EQ(runs.size(), 3u);
    double least = runs[0]["smoothing_cost"].get<double>();
    for (const auto& r : runs) least = std::min(least, r["smoothing_cost"].get<double>());
    for (const auto& r : runs) {
        if (r["seed"] == run["counts"]["kept_seed"]) {
            EXPECT_EQ(r["smoothing_cost"].get<double>(), least);
        }
    }
    const auto result = evaluate(out);
    ASSERT_TRUE(result.landmarks.has_value());
    EXPECT_EQ(result.landmarks->num_matched, 15u);
    EXPECT_LE(result.landmarks->num_estimated, 17u);
    ASSERT_EQ(result.robots.size(), 3u);
    for (const auto& robot : result.robots)
        EXPECT_LT(robot.estimate.unaligned.ate_rmse, 0.25) << robot.files.robot;
}
