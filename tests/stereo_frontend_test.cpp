// Runs the built stereo-frontend binary like a user would, on a small two-robot rawlog written
// here, and checks its output, its copies of the ground truth and its errors.
#include <gtest/gtest.h>
#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/obs/CObservationVisualLandmarks.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/test/RawlogInfo.h>
#include <mrpt_vslam/test/RunCommand.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using TRun = mrpt_vslam::test::TCommandResult;
using mrpt_vslam::test::runCommand;

using mrpt_vslam::test::lineCount;
using mrpt_vslam::test::parseRawlogInfo;
using mrpt_vslam::test::TRawlogInfo;

std::string fileBytes(const fs::path& file)
{
    std::ifstream in(file, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

constexpr int kWidth = 320, kHeight = 240, kFrames = 5;
constexpr int kDisparity = 16;     ///< px: a fronto-parallel wall at f·B/d = 280·0.12/16 = 2.1 m
constexpr int kShiftPerFrame = 8;  ///< px of image motion between frames

/** A cluttered random texture: overlapping rectangles of random gray levels on noise, box
 *  blurred. Wide enough for the image motion of all frames plus the disparity. */
std::vector<uint8_t> makeTexture(int width, int height, uint64_t seed)
{
    auto& rng = mrpt::random::getRandomGenerator();
    rng.randomize(seed);
    std::vector<double> t(static_cast<size_t>(width * height));
    for (double& v : t) v = rng.drawUniform(100, 156);
    for (int k = 0; k < width * height / 120; k++) {
        const int x0 = static_cast<int>(rng.drawUniform(0, width)),
                  y0 = static_cast<int>(rng.drawUniform(0, height));
        const int w = static_cast<int>(rng.drawUniform(3, 20)),
                  h = static_cast<int>(rng.drawUniform(3, 20));
        const double gray = rng.drawUniform(0, 255);
        for (int y = y0; y < std::min(height, y0 + h); y++)
            for (int x = x0; x < std::min(width, x0 + w); x++) t[y * width + x] = gray;
    }
    std::vector<uint8_t> out(t.size());
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            double s = 0;
            int n = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    const int xx = std::clamp(x + dx, 0, width - 1),
                              yy = std::clamp(y + dy, 0, height - 1);
                    s += t[yy * width + xx];
                    n++;
                }
            out[y * width + x] = static_cast<uint8_t>(s / n + 0.5);
        }
    return out;
}

/// The 320 × 240 window of the texture starting at column `x0`.
mrpt::img::CImage window(const std::vector<uint8_t>& tex, int tex_width, int x0)
{
    mrpt::img::CImage img(kWidth, kHeight, mrpt::img::CH_GRAY);
    for (int r = 0; r < kHeight; r++)
        for (int c = 0; c < kWidth; c++) *img(c, r) = tex[r * tex_width + x0 + c];
    return img;
}

/** Writes `DIR/walls.rawlog` (observation-only): per frame and robot a CObservationOdometry
 *  `<R>_ODOM` and a CObservationStereoImages `<R><stereo_suffix>` of a textured wall; R1's
 *  images are stored externally in `walls_Images/`, R2's inside the rawlog. Plus ground-truth
 *  files and an unrelated file beside it. Returns the rawlog path. */
std::string writeDataset(const fs::path& dir, const std::string& stereo_suffix = "_STEREO")
{
    fs::create_directories(dir / "walls_Images");
    const int tex_width = kWidth + kDisparity + kShiftPerFrame * kFrames + 8;
    const std::map<std::string, std::vector<uint8_t>> textures{
        {"R1", makeTexture(tex_width, kHeight, 1)}, {"R2", makeTexture(tex_width, kHeight, 2)}};
    mrpt::io::CFileGZOutputStream f((dir / "walls.rawlog").string());
    auto ar = mrpt::serialization::archiveFrom(f);
    for (int k = 0; k < kFrames; k++) {
        for (const auto& [robot, tex] : textures) {
            const auto t = mrpt::Clock::fromDouble(1.0e9 + k + (robot == "R2" ? 0.5 : 0.0));
            mrpt::obs::CObservationOdometry odo;
            odo.sensorLabel = robot + "_ODOM";
            odo.timestamp = t;
            odo.odometry = mrpt::poses::CPose2D(0.03 * k, 0, 0);
            ar << odo;

            mrpt::obs::CObservationStereoImages st;
            st.sensorLabel = robot + stereo_suffix;
            st.timestamp = t;
            // left pixel c shows texture column c + x0; right pixel c shows c + x0 + d
            const int x0 = 4 + kShiftPerFrame * k;
            st.imageLeft = window(tex, tex_width, x0);
            st.imageRight = window(tex, tex_width, x0 + kDisparity);
            st.hasImageRight = true;
            if (robot == "R1") {
                for (const auto& [img, side] :
                     std::initializer_list<std::pair<mrpt::img::CImage*, const char*>>{
                         {&st.imageLeft, "L"}, {&st.imageRight, "R"}}) {
                    const std::string name = robot + "_" + side + std::to_string(k) + ".png";
                    img->saveToFile((dir / "walls_Images" / name).string());
                    img->setExternalStorage(name);
                }
            }
            mrpt::img::TStereoCamera cam;
            cam.leftCamera.ncols = cam.rightCamera.ncols = kWidth;
            cam.leftCamera.nrows = cam.rightCamera.nrows = kHeight;
            cam.leftCamera.setIntrinsicParamsFromValues(280, 280, 159.5, 119.5);
            cam.rightCamera = cam.leftCamera;
            cam.rightCameraPose = mrpt::math::TPose3DQuat(0.12, 0, 0, 1, 0, 0, 0);
            st.setStereoCameraParams(cam);
            st.cameraPose = mrpt::poses::CPose3DQuat(
                mrpt::poses::CPose3D(0.1, 0.06, 0.5, -M_PI / 2, 0, -M_PI / 2));
            ar << st;
        }
    }
    std::ofstream(dir / "walls.groundtruth_R1.tum") << "# gt R1\n1000000000 0 0 0 0 0 0 1\n";
    std::ofstream(dir / "walls.groundtruth_R2.tum") << "# gt R2\n1000000000.5 -4 0 0 0 0 0 1\n";
    std::ofstream(dir / "walls.odometry_R1.tum") << "# odo R1\n1000000000 0 0 0 0 0 0 1\n";
    std::ofstream(dir / "walls.landmarks.txt") << "# id x y z\n0 1 2 0.5\n";
    std::ofstream(dir / "walls.notes.txt") << "not ground truth\n";
    return (dir / "walls.rawlog").string();
}

class StereoFrontendApp : public ::testing::Test {
  protected:
    static void SetUpTestSuite()
    {
        s_scratch = new mrpt_vslam::test::ScratchFolder("mrpt_vslam_stereo_frontend_test");
        s_rawlog = writeDataset(s_scratch->path() / "in");
        s_config = s_scratch->write("frontend.ini",
                                    "[StereoFrontEnd]\nmax_disparity = 64\n"
                                    "[MultiRobotSLAM]\nparticles = 100\n");
    }
    static void TearDownTestSuite()
    {
        delete s_scratch;
        s_scratch = nullptr;
    }

    /// Runs `stereo-frontend ARGS`.
    static TRun run(const std::string& args)
    {
        return runCommand(std::string(MRPT_VSLAM_BIN_DIR "/stereo-frontend ") + args,
                          s_scratch->path() / "command.log");
    }
    static std::string out(const std::string& name) { return s_scratch->file("out/" + name); }

    static mrpt_vslam::test::ScratchFolder* s_scratch;
    static std::string s_rawlog, s_config;
};
mrpt_vslam::test::ScratchFolder* StereoFrontendApp::s_scratch = nullptr;
std::string StereoFrontendApp::s_rawlog, StereoFrontendApp::s_config;

}  // namespace

TEST_F(StereoFrontendApp, TurnsStereoIntoLandmarksAndCopiesEverythingElse)
{
    const TRun r = run(s_config + " " + s_rawlog + " --out " + out("walls"));
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("stereo-frontend: wrote " + out("walls") +
                         ".rawlog: 10 stereo frames (R1_STEREO, R2_STEREO)"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("10 other observations copied, 4 ground-truth files copied"),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(out("walls.rawlog.tmp")));

    // Input and output entry by entry: same order, labels and timestamps.
    mrpt_vslam::core::RawlogReader in(s_rawlog), result(out("walls.rawlog"));
    std::map<std::string, std::vector<std::set<int64_t>>> ids;  // per label, per frame
    mrpt_vslam::core::TRawlogEntry a, b;
    size_t entries = 0;
    while (in.next(a)) {
        ASSERT_TRUE(result.next(b));
        ASSERT_TRUE(a.observation && b.observation);
        EXPECT_EQ(b.observation->timestamp, a.observation->timestamp);
        const std::string label = a.observation->sensorLabel;
        if (label.find("_ODOM") != std::string::npos) {
            EXPECT_EQ(b.observation->sensorLabel, label);
            EXPECT_TRUE(std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(b.observation));
        } else {
            const auto lm =
                std::dynamic_pointer_cast<mrpt::obs::CObservationVisualLandmarks>(b.observation);
            ASSERT_TRUE(lm) << label;
            const std::string robot = label.substr(0, 2);
            EXPECT_EQ(lm->sensorLabel, robot + "_LANDMARKS");
            EXPECT_EQ(lm->refCameraPose,
                      mrpt::poses::CPose3D(0.1, 0.06, 0.5, -M_PI / 2, 0, -M_PI / 2));
            std::set<int64_t> frame_ids;
            for (const auto& l : lm->landmarks.landmarks) {
                frame_ids.insert(l.ID);
                EXPECT_NEAR(l.pose_mean.z, 280 * 0.12 / kDisparity, 0.03);  // the wall, 2.1 m
                ASSERT_EQ(l.features.size(), 1u);
                EXPECT_EQ(l.features[0].descriptors.SURF.value_or(std::vector<float>()).size(),
                          64u);
            }
            ids[robot].push_back(frame_ids);
        }
        entries++;
    }
    EXPECT_FALSE(result.next(b));
    EXPECT_EQ(entries, 20u);
    for (const auto& [robot, frames] : ids) {
        ASSERT_EQ(frames.size(), static_cast<size_t>(kFrames)) << robot;
        EXPECT_TRUE(frames[0].empty() && frames[1].empty()) << robot;  // 3 frames first
        EXPECT_GE(frames[2].size(), 10u) << robot;
        // the same tracks go on: most ids of frame 3 are still there in frame 4
        size_t kept = 0;
        for (const int64_t id : frames[2]) kept += frames[3].count(id);
        EXPECT_GE(kept, frames[2].size() * 8 / 10) << robot;
    }

    // Ground truth copied byte for byte; other files beside the input are not.
    for (const std::string suffix :
         {".groundtruth_R1.tum", ".groundtruth_R2.tum", ".odometry_R1.tum", ".landmarks.txt"}) {
        ASSERT_TRUE(fs::exists(out("walls" + suffix))) << suffix;
        EXPECT_EQ(fileBytes(out("walls" + suffix)),
                  fileBytes(s_scratch->path() / "in" / ("walls" + suffix)));
        EXPECT_FALSE(fs::exists(out("walls" + suffix + ".tmp")));
    }
    EXPECT_FALSE(fs::exists(out("walls.notes.txt")));
}

// Stereo pairs under labels of the user's own are converted too, each label its own front-end,
// the landmarks labelled LABEL_LANDMARKS.
TEST_F(StereoFrontendApp, AnyStereoLabelIsConverted)
{
    const std::string rawlog = writeDataset(s_scratch->path() / "own", "_HEAD");
    const TRun r = run(s_config + " " + rawlog + " --out " + out("own"));
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("10 stereo frames (R1_HEAD, R2_HEAD)"), std::string::npos) << r.out;
    mrpt_vslam::core::RawlogReader result(out("own.rawlog"));
    std::map<std::string, size_t> landmarks;  // frames per label
    for (mrpt_vslam::core::TRawlogEntry e; result.next(e);)
        if (std::dynamic_pointer_cast<mrpt::obs::CObservationVisualLandmarks>(e.observation))
            landmarks[e.observation->sensorLabel]++;
    EXPECT_EQ(landmarks, (std::map<std::string, size_t>{{"R1_HEAD_LANDMARKS", kFrames},
                                                        {"R2_HEAD_LANDMARKS", kFrames}}));
}

TEST_F(StereoFrontendApp, RerunsGiveByteIdenticalRawlogs)
{
    ASSERT_EQ(run(s_config + " " + s_rawlog + " --quiet --out " + out("first/a")).exit_code, 0);
    const TRun r = run(s_config + " " + s_rawlog + " -q --out " + out("second/b"));
    ASSERT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.out, "");  // --quiet: nothing at all
    const std::string a = fileBytes(out("first/a.rawlog")), b = fileBytes(out("second/b.rawlog"));
    EXPECT_GT(a.size(), 10000u);
    EXPECT_EQ(a, b);
}

TEST_F(StereoFrontendApp, StockRawlogEditReadsTheOutput)
{
    if (!fs::exists("/usr/bin/rawlog-edit")) GTEST_SKIP() << "/usr/bin/rawlog-edit not installed";
    ASSERT_EQ(run(s_config + " " + s_rawlog + " -q --out " + out("stock/walls")).exit_code, 0);
    const TRun r = runCommand("/usr/bin/rawlog-edit --info -i '" + out("stock/walls.rawlog") + "'",
                              s_scratch->path() / "rawlog-edit.log");
    EXPECT_EQ(r.exit_code, 0) << r.out;
    TRawlogInfo info = parseRawlogInfo(r.out);
    EXPECT_EQ(info.fields["Overall number of objects"], "20") << r.out;
    const std::map<std::string, int> expected{
        {"R1_LANDMARKS", 5}, {"R1_ODOM", 5}, {"R2_LANDMARKS", 5}, {"R2_ODOM", 5}};
    EXPECT_EQ(info.sensor_counts, expected) << r.out;
    EXPECT_EQ(r.out.find("xception"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("not registered"), std::string::npos) << r.out;
}

TEST_F(StereoFrontendApp, ConfigurationErrorsExitWith2)
{
    const std::string args = " " + s_rawlog + " --out " + out("bad/x");
    const std::map<std::string, std::string> cases{
        {"[StereoFrontEnd]\nmax_corner = 100\n",
         "unknown key [StereoFrontEnd] max_corner (line 2)"},
        {"[StereoFrontEnd]\nmin_depth = 2\nmax_depth = 1\n",
         "[StereoFrontEnd] max_depth: must be finite and > min_depth"},
        {"[StereoFrontEnd]\nncc_window = 10\n", "[StereoFrontEnd] ncc_window: must be odd"}};
    int n = 0;
    for (const auto& [text, message] : cases) {
        const std::string cfg = s_scratch->write("bad" + std::to_string(n++) + ".ini", text);
        const TRun r = run(cfg + args);
        EXPECT_EQ(r.exit_code, 2) << text << r.out;
        EXPECT_EQ(lineCount(r.out), 1) << r.out;
        EXPECT_EQ(r.out.rfind("stereo-frontend: error: ", 0), 0u) << r.out;
        EXPECT_NE(r.out.find(message), std::string::npos) << r.out;
    }
    const TRun missing = run(s_scratch->file("nope.ini") + args);
    EXPECT_EQ(missing.exit_code, 2) << missing.out;
    EXPECT_NE(missing.out.find("nope.ini: cannot open configuration file"), std::string::npos)
        << missing.out;
    // writing over the input would lose it
    const TRun self = run(s_config + " " + s_rawlog + " --out " + s_scratch->file("in/walls"));
    EXPECT_EQ(self.exit_code, 2) << self.out;
    EXPECT_NE(self.out.find("would overwrite the input"), std::string::npos) << self.out;
    EXPECT_FALSE(fs::exists(out("bad/x.rawlog")));
}

TEST_F(StereoFrontendApp, CommandLineErrorsExitWith2AndHelpWith0)
{
    for (const std::string& args :
         {std::string(""), s_config, s_config + " " + s_rawlog,
          s_config + " " + s_rawlog + " --out", s_config + " " + s_rawlog + " extra --out x",
          s_config + " " + s_rawlog + " --qiet --out x"}) {
        const TRun r = run(args);
        EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.out;
        EXPECT_EQ(lineCount(r.out), 1) << args << "\n" << r.out;
        EXPECT_NE(r.out.find("(see stereo-frontend --help)"), std::string::npos) << r.out;
    }
    const TRun help = run("--help");
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_NE(help.out.find("Usage: stereo-frontend CONFIG.ini INPUT.rawlog --out DIR/NAME"),
              std::string::npos)
        << help.out;
    const TRun version = run("--version");
    EXPECT_EQ(version.exit_code, 0);
    EXPECT_EQ(version.out.rfind("stereo-frontend ", 0), 0u) << version.out;
    EXPECT_NE(version.out.find("(MRPT 2."), std::string::npos) << version.out;
}

TEST_F(StereoFrontendApp, BadDataExitsWith1AndLeavesNoOutput)
{
    const TRun missing =
        run(s_config + " " + s_scratch->file("none.rawlog") + " --out " + out("r1/x"));
    EXPECT_EQ(missing.exit_code, 1) << missing.out;
    EXPECT_NE(missing.out.find("none.rawlog: cannot open rawlog"), std::string::npos)
        << missing.out;

    // Only odometry: says what the rawlog holds.
    const fs::path odo_only = s_scratch->path() / "odo" / "odo.rawlog";
    fs::create_directories(odo_only.parent_path());
    {
        mrpt::io::CFileGZOutputStream f(odo_only.string());
        mrpt::obs::CObservationOdometry odo;
        odo.sensorLabel = "R1_ODOM";
        mrpt::serialization::archiveFrom(f) << odo << odo;
    }
    const TRun none = run(s_config + " " + odo_only.string() + " --out " + out("r2/x"));
    EXPECT_EQ(none.exit_code, 1) << none.out;
    EXPECT_EQ(lineCount(none.out), 1) << none.out;
    EXPECT_NE(none.out.find("found no CObservationStereoImages; the "
                            "rawlog has: 2 x CObservationOdometry (R1_ODOM)"),
              std::string::npos)
        << none.out;
    EXPECT_FALSE(fs::exists(out("r2/x.rawlog")));
    EXPECT_FALSE(fs::exists(out("r2/x.rawlog.tmp")));

    // Stereo pairs without a landmark: the error names the step that lost the points.
    const std::string far = s_scratch->write(
        "far.ini", "[StereoFrontEnd]\nmax_disparity = 64\nmin_depth = 50\nmax_depth = 60\n");
    const TRun empty = run(far + " " + s_rawlog + " -q --out " + out("r5/x"));
    EXPECT_EQ(empty.exit_code, 1) << empty.out;
    EXPECT_EQ(lineCount(empty.out), 1) << empty.out;
    EXPECT_NE(empty.out.find("walls.rawlog: no landmarks in 10 stereo pairs: none of the "),
              std::string::npos)
        << empty.out;
    // the walls stand at 280 px · 0.12 m / 16 px = 2.1 m (sub-pixel disparities: ± 0.05 m)
    EXPECT_TRUE(std::regex_search(empty.out,
                                  std::regex("matched corners lies within min_depth, max_depth = "
                                             "50, 60 m: they lie at 2\\.(0[5-9]|1[0-5])-"
                                             "2\\.(0[5-9]|1[0-5]) m \\(step 2")))
        << empty.out;
    EXPECT_FALSE(fs::exists(out("r5/x.rawlog")));
    EXPECT_FALSE(fs::exists(out("r5/x.rawlog.tmp")));

    // An external image is missing: the error names the entry and the file.
    const fs::path copy = s_scratch->path() / "broken";
    fs::create_directories(copy);
    fs::copy(s_scratch->path() / "in", copy, fs::copy_options::recursive);
    fs::remove(copy / "walls_Images" / "R1_R3.png");
    const TRun broken =
        run(s_config + " " + (copy / "walls.rawlog").string() + " -q --out " + out("r3/x"));
    EXPECT_EQ(broken.exit_code, 1) << broken.out;
    EXPECT_EQ(lineCount(broken.out), 1) << broken.out;
    EXPECT_NE(broken.out.find("walls.rawlog: entry 14, R1_STEREO (images '"), std::string::npos)
        << broken.out;
    EXPECT_NE(broken.out.find("R1_R3.png'; the external images of walls.rawlog are read from the "
                              "folder walls_Images beside it, else from Images)"),
              std::string::npos)
        << broken.out;
    EXPECT_FALSE(fs::exists(out("r3/x.rawlog")));
    EXPECT_FALSE(fs::exists(out("r3/x.rawlog.tmp")));
    EXPECT_FALSE(fs::exists(out("r3/x.groundtruth_R1.tum")));

    // The same failure over an earlier run's complete outputs: none of them is left standing.
    ASSERT_EQ(run(s_config + " " + s_rawlog + " -q --out " + out("r4/x")).exit_code, 0);
    ASSERT_TRUE(fs::exists(out("r4/x.rawlog")) && fs::exists(out("r4/x.groundtruth_R1.tum")));
    const TRun over =
        run(s_config + " " + (copy / "walls.rawlog").string() + " -q --out " + out("r4/x"));
    EXPECT_EQ(over.exit_code, 1) << over.out;
    for (const std::string suffix : {".rawlog", ".groundtruth_R1.tum", ".groundtruth_R2.tum",
                                     ".odometry_R1.tum", ".landmarks.txt"})
        EXPECT_FALSE(fs::exists(out("r4/x" + suffix))) << suffix;
}
