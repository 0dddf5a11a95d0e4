#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/test/RunFiles.h>
#include <mrpt_vslam/test/ScratchFolder.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

using mrpt_vslam::test::readJson;

using mrpt_vslam::core::LandmarkFile;
using mrpt_vslam::core::TumTrajectory;
namespace fs = std::filesystem;

namespace {

const mrpt_vslam::test::ScratchFolder& scratch()
{
    static const mrpt_vslam::test::ScratchFolder folder("vslam_eval_test");
    return folder;
}

/// A curvy planar path at 10 Hz, optionally shifted by (dx, dy).
TumTrajectory makePath(double dx = 0, double dy = 0, size_t n = 60)
{
    TumTrajectory p;
    for (size_t i = 0; i < n; i++) {
        const double a = 0.05 * i;
        p.push_back(500 + 0.1 * i, {4 * std::cos(a) + dx, 2 * std::sin(a) + dy, 0,
                                    mrpt::math::wrapToPi(a + M_PI / 2), 0, 0});
    }
    return p;
}

LandmarkFile landmarks(const std::vector<std::array<double, 3>>& xyz, int first_id)
{
    LandmarkFile f;
    for (const auto& p : xyz) {
        mrpt_vslam::core::TLandmark lm;
        lm.id = first_id++;
        lm.position = {p[0], p[1], p[2]};
        f.landmarks.push_back(lm);
    }
    return f;
}

struct TRunResult {
    int exit_code = -1;
    std::string stderr_text;
};

/// Under LeakSanitizer, ignores leaks inside the font and plugin loaders PLplot uses (third-party
/// allocations kept until exit); leaks in our code are still reported.
void suppressThirdPartyLeaks()
{
    if (std::getenv("LSAN_OPTIONS")) return;  // the caller's choice wins
    const auto file = (scratch().path() / "lsan.supp").string();
    std::ofstream(file) << "leak:libfontconfig.so\nleak:libltdl.so\nleak:libcairo.so\n"
                           "leak:libpango\n";
    ::setenv("LSAN_OPTIONS", ("suppressions=" + file).c_str(), 1);
}

TRunResult runApp(const std::string& app, const std::string& args)
{
    suppressThirdPartyLeaks();
    const auto errFile = (scratch().path() / "stderr.txt").string();
    const std::string cmd = std::string("\"") + MRPT_VSLAM_BIN_DIR "/" + app + "\" " + args +
                            " > /dev/null 2> \"" + errFile + "\"";
    const int status = std::system(cmd.c_str());
    TRunResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(errFile);
    std::ostringstream ss;
    ss << in.rdbuf();
    r.stderr_text = ss.str();
    return r;
}

TRunResult runEval(const std::string& args) { return runApp("vslam-eval", args); }

void expectNonEmptyPng(const fs::path& file)
{
    ASSERT_TRUE(fs::exists(file)) << file;
    EXPECT_GT(fs::file_size(file), 1000u) << file;
    std::ifstream in(file, std::ios::binary);
    char magic[4] = {};
    in.read(magic, 4);
    EXPECT_EQ(std::string(magic + 1, 3), "PNG") << file;
    EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
}

}  // namespace

TEST(VslamEval, LooseFilesGiveTheKnownOffset)
{
    const auto dir = scratch().path() / "loose";
    fs::create_directories(dir);
    makePath().save((dir / "gt.tum").string());
    makePath(0.3, -0.4).save((dir / "est.tum").string());
    landmarks({{0, 0, 0}, {5, 0, 0}, {0, 5, 0}, {-5, -5, 0}}, 0).save((dir / "lm.txt").string());
    // Map: two landmarks 0.1 m and 0.3 m off, one false far away; landmarks 2 and 3 missed
    // (the second estimate near landmark 0 is a duplicate).
    landmarks({{0.1, 0, 0}, {5, 0.3, 0}, {0, 0.5, 0}, {40, 40, 0}}, 10)
        .save((dir / "map.txt").string());
    const auto out = dir / "out";
    const auto r =
        runEval("--estimate " + (dir / "est.tum").string() + " --ground-truth " +
                (dir / "gt.tum").string() + " --landmarks-gt " + (dir / "lm.txt").string() +
                " --map " + (dir / "map.txt").string() + " --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    const auto j = readJson(out / "metrics.json");
    const auto& est = j["estimate"];
    EXPECT_EQ(est["matched_poses"].get<int>(), 60);
    EXPECT_NEAR(est["ate_rmse_m"].get<double>(), 0.5, 1e-6);
    EXPECT_NEAR(est["ate_mean_m"].get<double>(), 0.5, 1e-6);
    EXPECT_NEAR(est["ate_max_m"].get<double>(), 0.5, 1e-6);
    EXPECT_NEAR(est["heading_rmse_deg"].get<double>(), 0, 1e-4);
    EXPECT_DOUBLE_EQ(est["heading_share_under_threshold"].get<double>(), 1.0);
    EXPECT_NEAR(est["aligned_se2"]["ate_max_m"].get<double>(), 0, 1e-6);
    EXPECT_NEAR(est["aligned_se2"]["alignment"]["x_m"].get<double>(), -0.3, 1e-6);
    EXPECT_TRUE(j["odometry"].is_null());

    const auto& lm = j["landmarks"];
    EXPECT_EQ(lm["matched"].get<int>(), 2);
    EXPECT_EQ(lm["missed"].get<int>(), 2);
    EXPECT_EQ(lm["false"].get<int>(), 2);
    EXPECT_EQ(lm["duplicated"].get<int>(), 1);
    EXPECT_NEAR(lm["error_mean_m"].get<double>(), 0.2, 1e-6);
    EXPECT_NEAR(lm["error_max_m"].get<double>(), 0.3, 1e-6);
    ASSERT_EQ(lm["table"].size(), 4u);
    EXPECT_EQ(lm["table"][1]["est_id"].get<int>(), 11);
    EXPECT_NEAR(lm["table"][1]["ey"].get<double>(), 0.3, 1e-9);
    EXPECT_TRUE(lm["table"][3]["est_id"].is_null());
    EXPECT_EQ(j["map"]["elements"].get<int>(), 4);

    expectNonEmptyPng(out / "paths.png");
    expectNonEmptyPng(out / "errors.png");
    expectNonEmptyPng(out / "landmark_errors.png");
    EXPECT_FALSE(fs::exists(out / "metrics.json.tmp"));
    // evaluated again without landmarks: the earlier landmark plot does not stay beside it
    ASSERT_EQ(runEval("--estimate " + (dir / "est.tum").string() + " --ground-truth " +
                      (dir / "gt.tum").string() + " --out " + out.string())
                  .exit_code,
              0);
    EXPECT_TRUE(readJson(out / "metrics.json")["landmarks"].is_null());
    EXPECT_FALSE(fs::exists(out / "landmark_errors.png"));

    // --after: the poses later than t = 504.05 s only (504.1 to 505.9)
    const auto after = dir / "after";
    ASSERT_EQ(runEval("--estimate " + (dir / "est.tum").string() + " --ground-truth " +
                      (dir / "gt.tum").string() + " --after 504.05 --out " + after.string())
                  .exit_code,
              0);
    const auto ja = readJson(after / "metrics.json");
    EXPECT_EQ(ja["estimate"]["poses"].get<int>(), 19);
    EXPECT_EQ(ja["estimate"]["matched_poses"].get<int>(), 19);
    EXPECT_NEAR(ja["options"]["after_s"].get<double>(), 504.05, 1e-9);
    EXPECT_FALSE(j["options"].contains("after_s"));
}

TEST(VslamEval, RunFolderWithRobotsAndRunJson)
{
    const auto dir = scratch().path() / "multi";
    const auto run = dir / "run";
    fs::create_directories(run);
    makePath().save((dir / "scene.groundtruth_R1.tum").string());
    makePath(10, 0).save((dir / "scene.groundtruth_R2.tum").string());
    makePath(0, 0.5).save((run / "estimated_path_R1.tum").string());
    makePath(11, 0).save((run / "estimated_path_R2.tum").string());
    makePath(0, 2).save((run / "odometry_path_R1.tum").string());
    std::ofstream(run / "run.json")
        << nlohmann::json{{"ground_truth", (dir / "scene.rawlog").string()}};

    const auto r = runEval(run.string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    const auto j = readJson(run / "metrics.json");
    ASSERT_TRUE(j.contains("robots"));
    EXPECT_NEAR(j["robots"]["R1"]["estimate"]["ate_rmse_m"].get<double>(), 0.5, 1e-6);
    EXPECT_NEAR(j["robots"]["R1"]["odometry"]["ate_rmse_m"].get<double>(), 2.0, 1e-6);
    EXPECT_NEAR(j["robots"]["R2"]["estimate"]["ate_max_m"].get<double>(), 1.0, 1e-6);
    EXPECT_TRUE(j["robots"]["R2"]["odometry"].is_null());
    EXPECT_TRUE(j["landmarks"].is_null());
    expectNonEmptyPng(run / "paths.png");
    expectNonEmptyPng(run / "errors.png");
    EXPECT_FALSE(fs::exists(run / "landmark_errors.png"));

    // NAME.groundtruth.tum names the prefix NAME: each robot's own file
    const auto named =
        runEval(run.string() + " --ground-truth " + (dir / "scene.groundtruth.tum").string() +
                " --out " + (dir / "named").string());
    ASSERT_EQ(named.exit_code, 0) << named.stderr_text;
    const auto jn = readJson(dir / "named" / "metrics.json");
    EXPECT_NEAR(jn["robots"]["R2"]["estimate"]["ate_max_m"].get<double>(), 1.0, 1e-6);
    // any other TUM file is one robot's
    makePath().save((dir / "other.tum").string());
    const auto other = runEval(run.string() + " --ground-truth " + (dir / "other.tum").string());
    EXPECT_EQ(other.exit_code, 1);
    EXPECT_NE(other.stderr_text.find("other.tum: one ground-truth file for 2 robots"),
              std::string::npos)
        << other.stderr_text;
}

TEST(VslamEval, AGroundTruthFileBringsTheLandmarksBesideIt)
{
    const auto dir = scratch().path() / "beside";
    const auto run = dir / "run";
    fs::create_directories(run);
    makePath().save((dir / "hall.groundtruth.tum").string());
    landmarks({{0, 0, 0}, {5, 0, 0}}, 0).save((dir / "hall.landmarks.txt").string());
    makePath(0.3, -0.4).save((run / "estimated_path.tum").string());
    landmarks({{0.1, 0, 0}, {5, 0.3, 0}}, 0).save((run / "map.txt").string());

    const auto r =
        runEval(run.string() + " --ground-truth " + (dir / "hall.groundtruth.tum").string());
    ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
    const auto j = readJson(run / "metrics.json");
    EXPECT_NEAR(j["estimate"]["ate_rmse_m"].get<double>(), 0.5, 1e-6);
    EXPECT_EQ(j["landmarks"]["matched"].get<int>(), 2);
    EXPECT_NEAR(j["landmarks"]["error_mean_m"].get<double>(), 0.2, 1e-6);
    expectNonEmptyPng(run / "landmark_errors.png");
}

TEST(VslamEval, MissingFileFailsWithOneLineNamingIt)
{
    const auto dir = scratch().path() / "missing";
    fs::create_directories(dir);
    makePath().save((dir / "gt.tum").string());
    const auto missing = (dir / "nope.tum").string();
    const auto r = runEval("--estimate " + missing + " --ground-truth " +
                           (dir / "gt.tum").string() + " --out " + (dir / "out").string());
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(r.stderr_text.rfind("vslam-eval: error: " + missing + ": ", 0), 0u) << r.stderr_text;
    EXPECT_EQ(std::count(r.stderr_text.begin(), r.stderr_text.end(), '\n'), 1);
    EXPECT_FALSE(fs::exists(dir / "out" / "metrics.json"));
}

TEST(VslamEval, MalformedGroundTruthNamesFileAndLine)
{
    const auto dir = scratch().path() / "malformed";
    fs::create_directories(dir);
    makePath().save((dir / "est.tum").string());
    std::ofstream(dir / "gt.tum") << "500 0 0 0 0 0 0 1\n500.1 0 0 zero 0 0 0 1\n";
    const auto r = runEval("--estimate " + (dir / "est.tum").string() + " --ground-truth " +
                           (dir / "gt.tum").string() + " --out " + (dir / "out").string());
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.stderr_text.find((dir / "gt.tum").string() + ":2:"), std::string::npos)
        << r.stderr_text;
}

TEST(VslamEval, RunFolderWithoutGroundTruthIsAnError)
{
    const auto run = scratch().path() / "nogt";
    fs::create_directories(run);
    makePath().save((run / "estimated_path.tum").string());
    const auto r = runEval(run.string());
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.stderr_text.find("ground truth"), std::string::npos) << r.stderr_text;
    EXPECT_FALSE(fs::exists(run / "metrics.json"));
}

// A folder whose run stopped (run.json: completed false) holds nothing to evaluate; an option
// value out of its range is a usage error (exit 2).
TEST(VslamEval, AFailedRunOrAnOptionOutOfRangeIsRefused)
{
    const auto run = scratch().path() / "failed";
    fs::create_directories(run);
    makePath().save((run.parent_path() / "failed.groundtruth.tum").string());
    makePath().save((run / "estimated_path.tum").string());
    const auto gt = " --ground-truth " + (run.parent_path() / "failed").string();
    std::ofstream(run / "run.json")
        << nlohmann::json{{"completed", false}, {"error", "bad rawlog"}};
    const auto r = runEval(run.string() + gt);
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.stderr_text, "vslam-eval: error: " + (run / "run.json").string() +
                                 ": the run did not complete (bad rawlog): nothing to evaluate\n");
    EXPECT_FALSE(fs::exists(run / "metrics.json"));

    std::ofstream(run / "run.json") << nlohmann::json{{"completed", true}};
    EXPECT_EQ(runEval(run.string() + gt).exit_code, 0);
    for (const std::string option :
         {"--landmark-cutoff 0", "--time-tolerance -1", "--heading-threshold-deg -5"}) {
        const auto bad = runEval(run.string() + gt + " " + option);
        EXPECT_EQ(bad.exit_code, 2) << option;
        EXPECT_NE(bad.stderr_text.find(option.substr(0, option.find(' ')) + ": must be"),
                  std::string::npos)
            << bad.stderr_text;
    }
}

// vslam-plot: a table of two series with error bars becomes a PNG; a malformed line is a
// one-line error naming file and line, and no image is left behind.
TEST(VslamPlot, PlotsTablesAndRejectsMalformedOnes)
{
    const auto dir = scratch().path() / "plot";
    fs::create_directories(dir);
    std::ofstream(dir / "ok.txt")
        << "# series x y low high\nM=500 1 0.5 0.4 0.6\n"
           "M=500 10 0.3 0.2 0.4\nM=500 100 0.2 0.1 0.3\nB=8 1 0.6 0.5 0.7\n";
    const auto ok = runApp("vslam-plot", (dir / "ok.txt").string() + " " +
                                             (dir / "ok.png").string() + " --log-x --y-from-zero");
    EXPECT_EQ(ok.exit_code, 0) << ok.stderr_text;
    expectNonEmptyPng(dir / "ok.png");

    std::ofstream(dir / "bad.txt") << "A 1 2\nA 2 two\n";
    const auto bad =
        runApp("vslam-plot", (dir / "bad.txt").string() + " " + (dir / "bad.png").string());
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(bad.stderr_text.find("bad.txt:2: 'two' is not a finite number"), std::string::npos)
        << bad.stderr_text;
    EXPECT_EQ(std::count(bad.stderr_text.begin(), bad.stderr_text.end(), '\n'), 1);
    EXPECT_FALSE(fs::exists(dir / "bad.png"));

    std::ofstream(dir / "mixed.txt") << "A 1 2 1 3\nA 2 3\n";
    const auto mixed =
        runApp("vslam-plot", (dir / "mixed.txt").string() + " " + (dir / "mixed.png").string());
    EXPECT_EQ(mixed.exit_code, 1);
    EXPECT_NE(mixed.stderr_text.find("mixed.txt:2: series 'A' mixes"), std::string::npos)
        << mixed.stderr_text;

    std::ofstream(dir / "neg.txt") << "A 0 1\nA 1 2\n";
    const auto neg = runApp(
        "vslam-plot", (dir / "neg.txt").string() + " " + (dir / "neg.png").string() + " --log-x");
    EXPECT_EQ(neg.exit_code, 1);
    EXPECT_NE(neg.stderr_text.find("--log-x"), std::string::npos) << neg.stderr_text;
    EXPECT_FALSE(fs::exists(dir / "neg.png"));
}

// vslam-plot as a scatter plot against y = x (the peer comparison's figure), on log axes; the
// options that contradict it are one-line errors that leave no image.
TEST(VslamPlot, ScatterAgainstTheDiagonal)
{
    const auto dir = scratch().path() / "scatter";
    fs::create_directories(dir);
    std::ofstream(dir / "xy.txt") << "low 0.02 0.01\nlow 0.03 0.02\nhigh 0.2 0.1\nhigh 0.3 0.4\n";
    const auto plot = [&](const std::string& name, const std::string& options) {
        return runApp("vslam-plot",
                      (dir / "xy.txt").string() + " " + (dir / name).string() + " " + options);
    };
    const auto ok = plot("ok.png", "--points --diagonal --log-x --log-y");
    EXPECT_EQ(ok.exit_code, 0) << ok.stderr_text;
    expectNonEmptyPng(dir / "ok.png");
    const std::vector<std::pair<std::string, std::string>> bad = {
        {"--log-y --y-from-zero", "--y-from-zero and --log-y exclude each other"},
        {"--diagonal --log-x", "--diagonal needs both axes linear or both logarithmic"}};
    for (const auto& [options, message] : bad) {
        const auto r = plot("bad.png", options);
        EXPECT_EQ(r.exit_code, 1) << options;
        EXPECT_NE(r.stderr_text.find(message), std::string::npos) << r.stderr_text;
        EXPECT_FALSE(fs::exists(dir / "bad.png")) << options;
    }
    std::ofstream(dir / "zero.txt") << "A 1 0\nA 2 1\n";
    const auto zero = runApp(
        "vslam-plot", (dir / "zero.txt").string() + " " + (dir / "z.png").string() + " --log-y");
    EXPECT_EQ(zero.exit_code, 1);
    EXPECT_NE(zero.stderr_text.find("--log-y: series 'A' has a value <= 0"), std::string::npos)
        << zero.stderr_text;
}
