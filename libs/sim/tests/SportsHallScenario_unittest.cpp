#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/DatasetWriter.h>
#include <mrpt_vslam/sim/ScenarioFactory.h>
#include <mrpt_vslam/sim/SportsHallScenario.h>
#include <mrpt_vslam/test/RunFiles.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "TestConfig.h"

using mrpt_vslam::test::readBytes;

namespace fs = std::filesystem;
using namespace mrpt_vslam::sim;

namespace {

/// Runs the hall for `frames` frames into a fresh directory; returns the output prefix.
std::string runHall(const std::string& dir_name, uint64_t seed, int frames, bool images = true)
{
    const fs::path dir = mrpt_vslam::test::processScratchFolder() / dir_name;
    fs::remove_all(dir);
    auto scenario = createScenario("sports-hall");
    scenario->loadConfig(test::sportsHallConfig());
    TSimulationOptions opts;
    opts.out_prefix = (dir / "hall").string();
    opts.seed = seed;
    opts.frames = frames;
    opts.write_images = images;
    const TSimulationSummary s = scenario->run(opts);
    EXPECT_EQ(s.frames, frames);
    return opts.out_prefix;
}

std::vector<std::string> datasetFiles(const std::string& prefix)
{
    std::vector<std::string> files{".rawlog", ".groundtruth.tum", ".odometry.tum",
                                   ".landmarks.txt"};
    for (auto& f : files) f = prefix + f;
    for (int k = 0; k < 20; k++) {
        char name[64];
        std::snprintf(name, sizeof(name), "_Images/OMNICAM_%06d.png", k);
        files.push_back(prefix + name);
    }
    return files;
}

}  // namespace

TEST(SportsHallScenario, SameSeedGivesByteIdenticalFiles)
{
    const std::string a = runHall("seed1a", 1, 20), b = runHall("seed1b", 1, 20);
    const auto fa = datasetFiles(a), fb = datasetFiles(b);
    for (size_t i = 0; i < fa.size(); i++) {
        ASSERT_TRUE(fs::exists(fa[i])) << fa[i];
        EXPECT_EQ(readBytes(fa[i]), readBytes(fb[i])) << fa[i];
    }
    EXPECT_FALSE(fs::exists(a + ".rawlog.tmp"));
}

TEST(SportsHallScenario, DifferentSeedsGiveDifferentData)
{
    const std::string a = runHall("seed1c", 1, 20), b = runHall("seed2", 2, 20);
    EXPECT_NE(readBytes(a + ".rawlog"), readBytes(b + ".rawlog"));
    EXPECT_NE(readBytes(a + ".odometry.tum"), readBytes(b + ".odometry.tum"));
    EXPECT_NE(readBytes(a + "_Images/OMNICAM_000000.png"),
              readBytes(b + "_Images/OMNICAM_000000.png"));
    // The ground truth does not depend on the seed.
    EXPECT_EQ(readBytes(a + ".groundtruth.tum"), readBytes(b + ".groundtruth.tum"));
}

TEST(SportsHallScenario, ImagesDoNotChangeTheOtherRandomStreams)
{
    const std::string a = runHall("with_images", 3, 20, true),
                      b = runHall("no_images", 3, 20, false);
    EXPECT_EQ(readBytes(a + ".odometry.tum"), readBytes(b + ".odometry.tum"));
    EXPECT_FALSE(fs::exists(b + "_Images"));
}

TEST(SportsHallScenario, RawlogHoldsActionsAndFramesConsistentWithTheTextFiles)
{
    const std::string prefix = runHall("readback", 1, 20);
    const auto gt = mrpt_vslam::core::TumTrajectory::load(prefix + ".groundtruth.tum");
    ASSERT_EQ(gt.size(), 20u);

    mrpt::img::CImage::setImagesPathBase(prefix + "_Images");
    mrpt::io::CFileGZInputStream in(prefix + ".rawlog");
    auto ar = mrpt::serialization::archiveFrom(in);
    mrpt::obs::CActionCollection::Ptr acts;
    mrpt::obs::CSensoryFrame::Ptr sf;
    size_t index = 0;
    int frames = 0;
    while (mrpt::obs::CRawlog::readActionObservationPair(ar, acts, sf, index)) {
        ASSERT_TRUE(acts->getBestMovementEstimation());
        auto img = sf->getObservationBySensorLabelAs<mrpt::obs::CObservationImage::Ptr>("OMNICAM");
        auto brg = sf->getObservationBySensorLabelAs<mrpt::obs::CObservationBearingRange::Ptr>(
            "OMNICAM_BEARINGS");
        auto pose = sf->getObservationBySensorLabelAs<mrpt::obs::CObservationRobotPose::Ptr>(
            "GROUND_TRUTH");
        ASSERT_TRUE(img && brg && pose) << "frame " << frames;
        EXPECT_TRUE(img->image.isExternallyStored());
        EXPECT_EQ(img->image.getExternalStorageFile(),
                  DatasetWriter::imageFileName("OMNICAM", frames));
        // The external image loads lazily through MRPT: 640×480, one channel.
        EXPECT_EQ(img->image.getWidth(), 640u);
        EXPECT_EQ(img->image.getHeight(), 480u);
        EXPECT_FALSE(img->image.isColor());
        EXPECT_EQ(img->cameraPose, mrpt::poses::CPose3D(0, 0, 1.8, 0, 0, 0));
        EXPECT_EQ(brg->sensorLocationOnRobot, mrpt::poses::CPose3D(0, 0, 1.8, 0, 0, 0));
        EXPECT_TRUE(brg->validCovariances);
        EXPECT_GE(brg->sensedData.size(), 3u);
        for (const auto& m : brg->sensedData) {
            // per-measurement σ of 0.7 px through Eq. 1: a few mrad in φ and θ
            EXPECT_GT(m.covariance(1, 1), 1e-6);
            EXPECT_LT(m.covariance(1, 1), 1e-3);
            EXPECT_NEAR(m.covariance(2, 2), 0.0045 * 0.0045, 0.3 * 0.0045 * 0.0045);
            EXPECT_TRUE(std::isnan(m.range));
            EXPECT_EQ(m.landmarkID, -1);
            // θ ≤ max_light_theta (70°) up to the pixel noise: elevation above 19°
            EXPECT_LT(m.pitch, -mrpt::DEG2RAD(19.0));
        }
        EXPECT_NEAR(pose->pose.mean.x(), gt.poses[static_cast<size_t>(frames)].x, 1e-6);
        EXPECT_NEAR(mrpt::Clock::toDouble(pose->timestamp),
                    gt.timestamps[static_cast<size_t>(frames)], 1e-6);
        frames++;
    }
    EXPECT_EQ(frames, 20);
}

TEST(SportsHallScenario, RejectsATeam)
{
    auto scenario = createScenario("sports-hall");
    scenario->loadConfig(test::sportsHallConfig());
    TSimulationOptions opts;
    opts.out_prefix = (mrpt_vslam::test::processScratchFolder() / "team" / "hall").string();
    opts.robots = 2;
    EXPECT_THROW(scenario->run(opts), mrpt_vslam::core::UsageError);
    EXPECT_FALSE(fs::exists(opts.out_prefix + ".rawlog.tmp"));
}

TEST(SportsHallScenario, UnknownScenarioNamesTheKnownOnes)
{
    try {
        createScenario("gym");
        FAIL() << "no exception";
    } catch (const mrpt_vslam::core::UsageError& e) {
        EXPECT_NE(std::string(e.what()).find("sports-hall"), std::string::npos);
    }
}
