// The omni-fastslam driver on the shipped dataset: the run folder's outputs and failures on bad
// input.
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/filesystem.h>
#include <mrpt_vslam/apps/OmniFastSLAMApp.h>
#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/test/RewrittenRawlog.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <utility>
#include <vector>

using namespace mrpt_vslam;

namespace {
const std::string kSource = MRPT_VSLAM_SOURCE_DIR;
const std::string kConfig = kSource + "/share/mrpt-vslam/config/omni-fastslam/sports-hall.ini";
const std::string kRawlog = kSource + "/datasets/sports-hall/hall.rawlog";

core::AppArguments args(const std::vector<std::string>& extra)
{
    std::vector<const char*> argv{"omni-fastslam"};
    for (const auto& a : extra) argv.push_back(a.c_str());
    return core::AppArguments::parse(static_cast<int>(argv.size()), argv.data(), "omni-fastslam",
                                     "");
}

/// The error of a run with the shipped config on `rawlog` and the `extra` arguments, into
/// `out`; "ran" if it ran through.
std::string runError(const std::string& rawlog, const std::string& out,
                     const std::vector<std::string>& extra)
{
    std::vector<std::string> a{kConfig, rawlog, "--out", out, "--quiet"};
    a.insert(a.end(), extra.begin(), extra.end());
    apps::OmniFastSLAMApp app(args(a));
    app.initialize();
    try {
        app.run();
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "ran";
}
}  // namespace

TEST(OmniFastSLAMApp, WritesTheRunFolder)
{
    const test::ScratchFolder scratch("OmniFastSLAMApp_run");
    const auto out = scratch.file("out");
    apps::OmniFastSLAMApp app(args({kConfig, kRawlog, "--out", out, "--quiet"}));
    app.initialize();
    app.run();
    EXPECT_EQ(app.estimatedPath.size(), 320u);
    EXPECT_EQ(app.odometryPath.size(), 320u);
    for (const char* f : {"estimated_path.tum", "odometry_path.tum", "map.txt", "final_map.gz",
                          "final.3Dscene", "run.json", "config.ini", "metrics.json"})
        EXPECT_TRUE(mrpt::system::fileExists(out + "/" + f)) << f;
    const auto map = core::LandmarkFile::load(out + "/map.txt");
    EXPECT_GE(map.size(), 10u);
    EXPECT_LE(map.size(), 16u);
    for (const auto& lm : map.landmarks) EXPECT_TRUE(lm.has_cov);

    // The scene opens without the plugin: only stock opengl classes.
    mrpt::opengl::COpenGLScene scene;
    mrpt::io::CFileGZInputStream f(out + "/final.3Dscene");
    mrpt::serialization::archiveFrom(f) >> scene;
    EXPECT_GE(scene.getViewport()->size(), 4u);
}

TEST(OmniFastSLAMApp, ReadsObservationOnlyRawlogs)
{
    // The shipped rawlog rewritten in format #2: odometry readings + the frames' observations.
    const test::ScratchFolder scratch("OmniFastSLAMApp_format2");
    const auto rawlog = scratch.file("hall2.rawlog");
    test::rewriteRawlog(kRawlog, rawlog, true, false, [](const mrpt::obs::CObservation& o) {
        return o.sensorLabel != "OMNICAM";  // bearings + ground truth
    });
    apps::OmniFastSLAMApp app(args({kConfig, rawlog, "--out", scratch.file("out"), "--quiet",
                                    "--ground-truth", kSource + "/datasets/sports-hall/hall"}));
    app.initialize();
    app.run();
    EXPECT_EQ(app.estimatedPath.size(), 320u);
    const auto gt =
        core::TumTrajectory::load(kSource + "/datasets/sports-hall/hall.groundtruth.tum");
    const auto& last = app.estimatedPath.poses.back();
    const auto& truth = gt.poses.back();
    EXPECT_LT(std::hypot(last.x - truth.x, last.y - truth.y), 0.6);
}

TEST(OmniFastSLAMApp, RejectsAnUnknownKey)
{
    apps::OmniFastSLAMApp app(
        args({kConfig, kRawlog, "--set", "OmniFastSLAM.particle_cuont=3", "--quiet"}));
    EXPECT_THROW(app.initialize(), core::UsageError);
}

TEST(OmniFastSLAMApp, FailsOnAMissingRawlog)
{
    apps::OmniFastSLAMApp app(args({kConfig, "/nonexistent/x.rawlog", "--quiet"}));
    try {
        app.initialize();
        FAIL() << "no exception";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/x.rawlog"), std::string::npos);
    }
}

TEST(OmniFastSLAMApp, FailsOnAGroundTruthThatIsNotThere)
{
    const test::ScratchFolder scratch("OmniFastSLAMApp_truth");
    apps::OmniFastSLAMApp app(args(
        {kConfig, kRawlog, "--out", scratch.file("out"), "--quiet", "--ground-truth", "/no/gt"}));
    try {
        app.initialize();
        ADD_FAILURE() << "started without its ground truth";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "--ground-truth /no/gt: no such file: /no/gt.groundtruth.tum");
    }
}

TEST(OmniFastSLAMApp, FailsOnARawlogWithoutLightMeasurements)
{
    // A rawlog whose frames hold neither bearings nor images of the configured labels.
    const test::ScratchFolder scratch("OmniFastSLAMApp_nolights");
    const auto out = scratch.file("out");
    apps::OmniFastSLAMApp app(
        args({kConfig, kRawlog, "--out", out, "--quiet", "--set",
              "OmniFastSLAM.bearings_label=NONE", "--set", "OmniFastSLAM.image_label=NONE"}));
    app.initialize();
    try {
        app.run();
        ADD_FAILURE() << "ran without light measurements";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(
                      ": no ceiling-light measurements (CObservationBearingRange labelled 'NONE' "
                      "or CObservationImage labelled 'NONE'); the rawlog has: "),
                  std::string::npos)
            << e.what();
    }
    // the run.json of a run that failed says so, and no other output stands as if whole
    std::ifstream in(out + "/run.json");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("\"completed\": false"), std::string::npos) << text;
    EXPECT_NE(text.find("NONE"), std::string::npos) << text;
    EXPECT_FALSE(mrpt::system::fileExists(out + "/estimated_path.tum"));
    EXPECT_FALSE(mrpt::system::fileExists(out + "/metrics.json"));
}

// `input` chooses where the lights come from: with `images`, a rawlog with bearings but none of
// the configured images is refused (it used to run on the bearings), and each choice names
// only its own input.
TEST(OmniFastSLAMApp, TheChosenInputIsTheOnlyOne)
{
    const test::ScratchFolder scratch("OmniFastSLAMApp_input");
    const auto errorOf = [&](const std::vector<std::string>& extra) {
        return runError(kRawlog, scratch.file("out"), extra);
    };
    const std::string has =
        "; the rawlog has: 320 x CActionRobotMovement2D, 320 x CObservationBearingRange "
        "(OMNICAM_BEARINGS), 320 x CObservationImage (OMNICAM), 320 x CObservationRobotPose "
        "(GROUND_TRUTH)";
    EXPECT_EQ(
        errorOf({"--set", "OmniFastSLAM.input=images", "--set", "OmniFastSLAM.image_label=NONE"}),
        kRawlog + ": no ceiling-light measurements (CObservationImage labelled 'NONE')" + has);
    EXPECT_EQ(errorOf({"--set", "OmniFastSLAM.input=bearings", "--set",
                       "OmniFastSLAM.bearings_label=NONE"}),
              kRawlog + ": no ceiling-light measurements (CObservationBearingRange labelled " +
                  "'NONE')" + has);
}

// Images of the camera in which the detector finds no light (blobs of at least 3999 px; the
// hall's lights are smaller), and bearing observations that hold no bearing, say so (and which
// keys set the detector) rather than that the rawlog has no such observations.
TEST(OmniFastSLAMApp, SaysWhenTheFramesHoldNoLight)
{
    const test::ScratchFolder scratch("OmniFastSLAMApp_nolight");
    const auto errorOf = [&](const std::string& rawlog, const std::vector<std::string>& extra) {
        return runError(rawlog, scratch.file("out"), extra);
    };
    EXPECT_EQ(errorOf(kRawlog, {"--set", "OmniFastSLAM.input=images", "--set",
                                "LightDetector.min_blob_area=3999"}),
              kRawlog +
                  ": no ceiling-light measurement in any frame: no light was detected in the 320 "
                  "images (CObservationImage labelled 'OMNICAM'): check [LightDetector] "
                  "intensity_threshold, min_blob_area, max_blob_area and [Camera] "
                  "(doc/omni-fastslam.md)");
    const auto empty = scratch.file("empty-bearings.rawlog");
    test::rewriteRawlog(kRawlog, empty, false, false, [](mrpt::obs::CObservation& o) {
        if (auto* b = dynamic_cast<mrpt::obs::CObservationBearingRange*>(&o)) b->sensedData.clear();
        return o.sensorLabel != "OMNICAM";  // bearings + ground truth
    });
    EXPECT_EQ(errorOf(empty, {}),
              empty +
                  ": no ceiling-light measurement in any frame: the 320 frames' "
                  "CObservationBearingRange labelled 'OMNICAM_BEARINGS' hold no bearing");
}

// An image file cut short (OpenCV would decode its missing part grey, without an error) stops the
// run at its frame, naming the file
TEST(OmniFastSLAMApp, RefusesATruncatedImageFile)
{
    const test::ScratchFolder scratch("OmniFastSLAMApp_truncated");
    const auto images = scratch.path() / "hall_Images";
    std::filesystem::copy_file(kRawlog, scratch.file("hall.rawlog"));
    std::filesystem::copy(kSource + "/datasets/sports-hall/hall_Images", images);
    const auto cut = images / "OMNICAM_000004.png";
    std::filesystem::resize_file(cut, std::filesystem::file_size(cut) / 2);
    EXPECT_EQ(runError(scratch.file("hall.rawlog"), scratch.file("out"),
                       {"--set", "OmniFastSLAM.input=images"}),
              scratch.file("hall.rawlog") + ": frame 4: cannot use OMNICAM '" + cut.string() +
                  "': the image's file is truncated (a PNG whose last chunk is cut short)");
}

// A frame with more bearings than max_bearings_per_frame stops the run with one line naming it
// (the shipped hall's frames hold 4 to 12 lights).
TEST(OmniFastSLAMApp, RefusesAFrameWithTooManyBearings)
{
    const test::ScratchFolder scratch("OmniFastSLAMApp_bearings");
    apps::OmniFastSLAMApp app(args({kConfig, kRawlog, "--out", scratch.file("out"), "--quiet",
                                    "--set", "OmniFastSLAM.max_bearings_per_frame=2"}));
    app.initialize();
    try {
        app.run();
        FAIL() << "a frame with more bearings than allowed was accepted";
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("bearings in one frame, more than max_bearings_per_frame = 2"),
                  std::string::npos)
            << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

// A config kept in the run folder as config.ini, the name of the effective configuration the run
// writes there, is refused before anything is written: it would be lost.
TEST(OmniFastSLAMApp, RefusesAnInputItWouldWriteOver)
{
    const test::ScratchFolder scratch("OmniFastSLAMApp_input");
    const std::string out = scratch.file("exp1");
    std::filesystem::create_directories(out);
    const std::string config = out + "/config.ini";
    std::filesystem::copy_file(kConfig, config);
    const auto before = std::filesystem::file_size(config);
    apps::OmniFastSLAMApp app(args({config, kRawlog, "--out", out, "--quiet"}));
    app.initialize();
    try {
        app.run();
        ADD_FAILURE() << "ran over its own config";
    } catch (const core::UsageError& e) {
        EXPECT_EQ(std::string(e.what()), config + ": a file the run writes in its folder " + out +
                                             ": rename it, or choose another --out");
    }
    EXPECT_EQ(std::filesystem::file_size(config), before);
    EXPECT_FALSE(std::filesystem::exists(out + "/run.json"));
}

// The paths are stamped with the steps' times: a frame stamped as the one before it, or not at
// all, stops the run with one line naming the step (its frames are stamped 1 s apart).
TEST(OmniFastSLAMApp, RefusesStepsWithoutTimesAfterTheStepBefore)
{
    const test::ScratchFolder scratch("OmniFastSLAMApp_stamps");
    for (const bool unstamped : {false, true}) {
        const std::string rawlog = scratch.file(unstamped ? "unstamped.rawlog" : "same.rawlog");
        {
            mrpt::io::CFileGZOutputStream f(rawlog);
            auto ar = mrpt::serialization::archiveFrom(f);
            core::RawlogReader reader(kRawlog);
            mrpt::Clock::time_point previous;
            for (core::TRawlogEntry e; reader.next(e);) {
                ASSERT_TRUE(e.actions && e.observations);
                if (e.index == 5)
                    for (auto& obs : *e.observations)
                        obs->timestamp = unstamped ? INVALID_TIMESTAMP : previous;
                previous = (*e.observations->begin())->timestamp;
                ar << *e.actions << *e.observations;
            }
        }
        apps::OmniFastSLAMApp app(args({kConfig, rawlog, "--out", scratch.file("out"), "-q"}));
        app.initialize();
        try {
            app.run();
            ADD_FAILURE() << rawlog << ": ran";
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()),
                      rawlog +
                          (unstamped ? ": step 5 has no timestamp"
                                     : ": step 5 at 1325376004.000000 s is not after step 4 at "
                                       "1325376004.000000 s") +
                          ": the paths are stamped with the steps' times");
        }
    }
}

// Impossible or misread values: a usage error naming the key and the problem, in one line.
TEST(OmniFastSLAMApp, RejectsImpossibleValuesNamingTheKey)
{
    const std::vector<std::pair<std::string, std::string>> impossible = {
        {"ParticleFilter.sampleSize=1e12", "[ParticleFilter] sampleSize = 1e12: not an integer"},
        {"ParticleFilter.sampleSize=0", "sampleSize must be 1 to 100000"},
        {"ParticleFilter.BETA=nan", "[ParticleFilter] BETA = nan: not a finite number"},
        {"ParticleFilter.BETA=-1", "BETA (the N_eff/N threshold of resampling) must be in"},
        {"ParticleFilter.powFactor=nan", "[ParticleFilter] powFactor = nan: not a finite number"},
        {"ParticleFilter.powFactor=0", "powFactor must be in (0, 1]"},
        {"ParticleFilter.PF_algorithm=bogus",
         "[ParticleFilter] PF_algorithm must be pfStandardProposal or pfOptimalProposal, not "
         "'bogus'"},
        {"ParticleFilter.PF_algorithm=pfAuxiliaryPFOptimal",
         "[ParticleFilter] PF_algorithm must be pfStandardProposal or pfOptimalProposal, not "
         "'pfAuxiliaryPFOptimal'"},
        {"ParticleFilter.resamplingMethod=9",
         "[ParticleFilter] resamplingMethod must be "
         "prMultinomial, prResidual, prStratified or prSystematic, not '9'"},
        {"ParticleFilter.max_loglikelihood_dyn_range=-1",
         "[ParticleFilter] max_loglikelihood_dyn_range must be finite and > 0"},
        {"MappingApplication_ceilingLightsMap_00_insertOpts.association_method=7",
         "[MappingApplication_ceilingLightsMap_00_insertOpts] association_method must be "
         "hungarian or ml, not '7'"},
        {"MappingApplication_ceilingLightsMap_00_creationOpts.measurement_model=Planar",
         "[MappingApplication_ceilingLightsMap_00_creationOpts] measurement_model must be "
         "spherical or planar, not 'Planar'"},
        {"MappingApplication.COccupancyGridMap2D_count=-1",
         "[MappingApplication] COccupancyGridMap2D_count = -1: a count of maps must be 0 or more"},
        {"ParticleFilter.adaptiveSampleSize=maybe",
         "adaptiveSampleSize = maybe: not a boolean (true, false) or an integer"},
        {"MotionModel.a1=inf", "[MotionModel] a1 = inf: not a finite number"},
        {"MotionModel.a1=-1", "[MotionModel] a1: must be finite and >= 0"},
        {"MotionModel.minStdXY=0", "[MotionModel] minStdXY: must be finite and > 0"},
        {"OmniFastSLAM.min_motion_std_phi_deg=-1", "min_motion_std_phi_deg: must be > 0"},
        {"OmniFastSLAM.min_motion_std_xy=abc", "min_motion_std_xy = abc: not a number"},
        {"OmniFastSLAM.max_bearings_per_frame=0", "max_bearings_per_frame must be >= 1"},
        {"OmniFastSLAM.filter_runs=0",
         "[OmniFastSLAM] filter_runs must be an integer from 1 to 64"},
        {"OmniFastSLAM.filter_runs=1.5", "[OmniFastSLAM] filter_runs = 1.5: not an integer"}};
    for (const auto& [setting, message] : impossible) {
        apps::OmniFastSLAMApp app(args({kConfig, kRawlog, "--set", setting, "--quiet"}));
        try {
            app.initialize();
            ADD_FAILURE() << setting << " accepted";
        } catch (const core::UsageError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(message), std::string::npos) << setting << ": " << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
}

// Filters run side by side are compared by their smoothed cost: without the smoothing there is
// nothing to compare them by.
TEST(OmniFastSLAMApp, FilterRunsNeedTheSmoothing)
{
    apps::OmniFastSLAMApp app(args({kConfig, kRawlog, "--set", "OmniFastSLAM.filter_runs=2",
                                    "--set", "LightsPathSmoother.smooth_path=false", "--quiet"}));
    try {
        app.initialize();
        ADD_FAILURE() << "filter_runs = 2 without smoothing accepted";
    } catch (const core::UsageError& e) {
        EXPECT_NE(
            std::string(e.what()).find(
                "[OmniFastSLAM] filter_runs > 1 needs [LightsPathSmoother] smooth_path = true"),
            std::string::npos)
            << e.what();
    }
}
