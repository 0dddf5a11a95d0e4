#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/sim/DatasetWriter.h>
#include <mrpt_vslam/sim/OmniViewsScenario.h>
#include <mrpt_vslam/sim/ScenarioFactory.h>
#include <mrpt_vslam/test/RunFiles.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <opencv2/core.hpp>

using mrpt_vslam::test::readBytes;

namespace fs = std::filesystem;
using namespace mrpt_vslam::sim;

namespace {

std::string shippedIni()
{
    return std::string(MRPT_VSLAM_SOURCE_DIR) + "/share/mrpt-vslam/config/vslam-sim/omni-views.ini";
}

/// The shipped scenario, loaded once.
const OmniViewsScenario& shipped()
{
    static const OmniViewsScenario scenario = [] {
        OmniViewsScenario s;
        s.loadConfig(mrpt::config::CConfigFile(shippedIni()));
        return s;
    }();
    return scenario;
}

/// Runs the shipped scenario (created by name) into a fresh directory; returns the prefix.
std::string runOmni(const std::string& dir_name, uint64_t seed, int frames, bool images)
{
    const fs::path dir = mrpt_vslam::test::processScratchFolder() / dir_name;
    fs::remove_all(dir);
    const std::unique_ptr<Scenario> scenario = createScenario("omni-views");
    scenario->loadConfig(mrpt::config::CConfigFile(shippedIni()));
    TSimulationOptions opts;
    opts.out_prefix = (dir / "omni").string();
    opts.seed = seed;
    opts.frames = frames;
    opts.write_images = images;
    const TSimulationSummary s = scenario->run(opts);
    EXPECT_EQ(s.frames, frames < 0 ? shipped().trajectory.frames : frames);
    EXPECT_EQ(s.robots, 1);
    return opts.out_prefix;
}

mrpt::poses::CPose2D pose2d(const mrpt::math::TPose3D& p) { return {p.x, p.y, p.yaw}; }

}  // namespace

TEST(OmniViewsScenario, PathStaysInFreeSpaceAndClosesTwoLoops)
{
    const OmniViewsScenario& s = shipped();
    const auto path = s.trajectory.generate(s.trajectory.frames);
    double min_clearance = 1e9, max_step = 0, max_turn = 0, length = 0;
    double x_min = 1e9, x_max = -1e9, y_min = 1e9, y_max = -1e9;
    for (size_t k = 0; k < path.size(); k++) {
        min_clearance = std::min(min_clearance, s.world.clearance(path[k].x, path[k].y));
        x_min = std::min(x_min, path[k].x), x_max = std::max(x_max, path[k].x);
        y_min = std::min(y_min, path[k].y), y_max = std::max(y_max, path[k].y);
        if (k == 0) continue;
        const double step = std::hypot(path[k].x - path[k - 1].x, path[k].y - path[k - 1].y);
        length += step;
        max_step = std::max(max_step, step);
        max_turn =
            std::max(max_turn, std::abs(mrpt::math::wrapToPi(path[k].phi - path[k - 1].phi)));
    }
    // Loop closures: frames back within 0.3 m of a pose at least 80 frames earlier (heading
    // free: an omnidirectional view is recognised from any heading); separate events need
    // 40 frames away from any earlier place in between.
    std::vector<size_t> closures;
    bool inside = false;
    for (size_t b = 80; b < path.size(); b++) {
        bool revisit = false;
        for (size_t a = 0; a + 80 <= b && !revisit; a++)
            revisit = std::hypot(path[b].x - path[a].x, path[b].y - path[a].y) < 0.3;
        if (revisit && !inside && (closures.empty() || b > closures.back() + 40))
            closures.push_back(b);
        inside = revisit;
    }
    std::cout << path.size() << " frames, " << length << " m, area x " << x_min << ".." << x_max
              << " y " << y_min << ".." << y_max << "; min clearance " << min_clearance
              << " m, max step " << max_step << " m, max turn " << mrpt::RAD2DEG(max_turn)
              << " deg; revisits start at frames";
    for (size_t c : closures) std::cout << " " << c;
    std::cout << "\n";
    EXPECT_GE(min_clearance, s.robot_radius);
    EXPECT_LE(max_step, 0.151);
    EXPECT_GE(max_step, 0.1);
    EXPECT_LE(max_turn, mrpt::DEG2RAD(12.1));
    EXPECT_GE(closures.size(), 2u);
    EXPECT_GE(x_max - x_min, 10.0);
    EXPECT_GE(y_max - y_min, 5.0);
}

TEST(OmniViewsScenario, EveryRayHitsTheWorldAndWallsFillTheImage)
{
    const OmniViewsScenario& s = shipped();
    const TOfficeModel model = s.world.build(s.textures);
    const auto path = s.trajectory.generate(s.trajectory.frames);
    const size_t ceiling = model.scene.rectangles.size() - 1;  // last face (OfficeWorld order)
    double min_hit = 1, min_vertical = 1, min_ceiling = 1;
    for (size_t k = 0; k < path.size(); k += 30) {
        const mrpt::poses::CPose3D cam =
            mrpt::poses::CPose3D(mrpt::poses::CPose2D(path[k])) + s.camera_on_robot;
        const TRenderedView v = s.renderer.renderView(model.scene, cam);
        size_t valid = 0, hit = 0, vertical = 0, on_ceiling = 0;
        for (size_t i = 0; i < v.face.size(); i++) {
            const auto ray = s.renderer.camera().unproject(
                Eigen::Vector2d(static_cast<double>(i % static_cast<size_t>(v.width)),
                                static_cast<double>(i / static_cast<size_t>(v.width))));
            if (!ray) {
                EXPECT_EQ(v.face[i], -1);
                continue;
            }
            valid++;
            if (v.face[i] < 0) continue;
            hit++;
            vertical += model.scene.rectangles[static_cast<size_t>(v.face[i])].isVertical();
            on_ceiling += static_cast<size_t>(v.face[i]) == ceiling;
        }
        min_hit = std::min(min_hit, static_cast<double>(hit) / valid);
        min_vertical = std::min(min_vertical, static_cast<double>(vertical) / valid);
        min_ceiling = std::min(min_ceiling, static_cast<double>(on_ceiling) / valid);
    }
    std::cout << "over the frames: at least " << 100 * min_vertical << " % of the image circle on "
              << "walls and furniture, " << 100 * min_ceiling << " % on the ceiling; "
              << model.corners.size() << " texture corners\n";
    EXPECT_EQ(min_hit, 1.0) << "inside the closed world every ray hits a face";
    EXPECT_GE(min_vertical, 0.4);
    EXPECT_GE(min_ceiling, 0.05);
}

TEST(OmniViewsScenario, RawlogHoldsOdometryImageAndGroundTruthPerFrame)
{
    constexpr int kFrames = 4;
    const std::string prefix = runOmni("readback", 1, kFrames, true);
    const OmniViewsScenario& s = shipped();
    const auto gt = mrpt_vslam::core::TumTrajectory::load(prefix + ".groundtruth.tum");
    const auto odo = mrpt_vslam::core::TumTrajectory::load(prefix + ".odometry.tum");
    ASSERT_EQ(gt.size(), static_cast<size_t>(kFrames));
    ASSERT_EQ(odo.timestamps, gt.timestamps);
    EXPECT_GT(mrpt_vslam::core::LandmarkFile::load(prefix + ".landmarks.txt").size(), 100u);

    mrpt_vslam::core::RawlogReader reader(prefix + ".rawlog");
    size_t frames = 0;
    for (mrpt_vslam::core::TRawlogEntry e; reader.next(e);) {
        ASSERT_TRUE(e.actions && e.observations) << "format #1, entry " << e.index;
        const double t = s.start_time + frames * s.trajectory.frame_period;
        EXPECT_NEAR(mrpt::Clock::toDouble(e.timestamp), t, 1e-6);
        EXPECT_NEAR(gt.timestamps[frames], t, 1e-6);
        auto move = e.actions->getBestMovementEstimation();
        ASSERT_TRUE(move);
        auto image = e.observations->getObservationByClass<mrpt::obs::CObservationImage>();
        ASSERT_TRUE(image);
        EXPECT_EQ(image->sensorLabel, "OMNICAM");
        EXPECT_EQ(image->image.getExternalStorageFile(),
                  DatasetWriter::imageFileName("OMNICAM", static_cast<int>(frames)));
        EXPECT_EQ(image->image.getWidth(), 640u);
        EXPECT_EQ(image->image.getHeight(), 480u);
        EXPECT_FALSE(image->image.isColor());
        EXPECT_EQ(image->cameraPose.z(), 0.4);
        auto truth = e.observations->getObservationByClass<mrpt::obs::CObservationRobotPose>();
        ASSERT_TRUE(truth);
        EXPECT_EQ(truth->sensorLabel, "GROUND_TRUTH");
        EXPECT_NEAR(truth->pose.mean.x(), gt.poses[frames].x, 1e-6);
        EXPECT_NEAR(truth->pose.mean.y(), gt.poses[frames].y, 1e-6);
        frames++;
    }
    EXPECT_EQ(frames, static_cast<size_t>(kFrames));
    const auto& sum = reader.summary();
    EXPECT_EQ(sum.format(), mrpt_vslam::core::RawlogFormat::ActionObservationPairs);
    EXPECT_EQ(sum.count("CObservationImage", "OMNICAM"), static_cast<size_t>(kFrames));
    EXPECT_EQ(sum.count("CObservationRobotPose", "GROUND_TRUTH"), static_cast<size_t>(kFrames));
    EXPECT_EQ(sum.count("CActionRobotMovement2D"), static_cast<size_t>(kFrames));
    std::cout << "rawlog: " << sum.describe() << "\n";

    // Images on disk: 640 × 480 gray PNG, black outside the image circle.
    size_t bytes = 0;
    for (int k = 0; k < kFrames; k++) {
        const fs::path file =
            fs::path(prefix + "_Images") / DatasetWriter::imageFileName("OMNICAM", k);
        ASSERT_TRUE(fs::exists(file)) << file;
        bytes += fs::file_size(file);
        mrpt::img::CImage img;
        ASSERT_TRUE(img.loadFromFile(file.string(), 0));
        EXPECT_EQ(img.getWidth(), 640u);
        EXPECT_EQ(img.getHeight(), 480u);
        EXPECT_EQ(img.asCvMatRef().at<uint8_t>(0, 0), 0);
        EXPECT_GT(img.asCvMatRef().at<uint8_t>(239, 319), 0);
    }
    std::cout << "PNG size " << bytes / kFrames / 1024 << " KiB per frame\n";
}

TEST(OmniViewsScenario, SameSeedGivesByteIdenticalFilesOtherSeedOtherNoise)
{
    const std::string a = runOmni("seed1a", 1, 3, true), b = runOmni("seed1b", 1, 3, true);
    std::vector<std::string> files{".rawlog", ".groundtruth.tum", ".odometry.tum",
                                   ".landmarks.txt"};
    for (int k = 0; k < 3; k++)
        files.push_back("_Images/" + DatasetWriter::imageFileName("OMNICAM", k));
    for (const std::string& f : files) {
        ASSERT_TRUE(fs::exists(a + f)) << f;
        EXPECT_EQ(readBytes(a + f), readBytes(b + f)) << f;
    }
    EXPECT_FALSE(fs::exists(a + ".rawlog.tmp"));

    const std::string c = runOmni("seed2", 2, 3, true);
    EXPECT_NE(readBytes(a + ".rawlog"), readBytes(c + ".rawlog"));
    EXPECT_NE(readBytes(a + ".odometry.tum"), readBytes(c + ".odometry.tum"));
    EXPECT_NE(readBytes(a + "_Images/OMNICAM_000002.png"),
              readBytes(c + "_Images/OMNICAM_000002.png"));
    // The world and the path do not depend on the seed.
    EXPECT_EQ(readBytes(a + ".groundtruth.tum"), readBytes(c + ".groundtruth.tum"));
    EXPECT_EQ(readBytes(a + ".landmarks.txt"), readBytes(c + ".landmarks.txt"));
}

TEST(OmniViewsScenario, OdometryFollowsTheConfiguredNoise)
{
    const std::string prefix = runOmni("odometry", 5, -1, false);
    EXPECT_FALSE(fs::exists(prefix + "_Images/OMNICAM_000000.png"));
    const auto gt = mrpt_vslam::core::TumTrajectory::load(prefix + ".groundtruth.tum");
    const auto odo = mrpt_vslam::core::TumTrajectory::load(prefix + ".odometry.tum");
    ASSERT_EQ(gt.size(), static_cast<size_t>(shipped().trajectory.frames));
    ASSERT_EQ(odo.timestamps, gt.timestamps);
    EXPECT_EQ(odo.poses.front(), gt.poses.front()) << "starts at the true pose";
    double mahalanobis = 0;
    for (size_t k = 1; k < gt.size(); k++) {
        const mrpt::poses::CPose2D truth = pose2d(gt.poses[k]) - pose2d(gt.poses[k - 1]);
        const mrpt::poses::CPose2D noisy = pose2d(odo.poses[k]) - pose2d(odo.poses[k - 1]);
        mrpt::obs::CActionRobotMovement2D a;
        a.computeFromOdometry(truth, shipped().odometry.motionModel());
        mrpt::math::CMatrixDouble33 cov;
        mrpt::poses::CPose2D mean;
        a.poseChange->getCovarianceAndMean(cov, mean);
        const Eigen::Vector3d e(noisy.x() - truth.x(), noisy.y() - truth.y(),
                                mrpt::math::wrapToPi(noisy.phi() - truth.phi()));
        mahalanobis += e.dot(cov.asEigen().inverse() * e);
    }
    mahalanobis /= static_cast<double>(gt.size() - 1);
    const mrpt::poses::CPose2D end_error = pose2d(odo.poses.back()) - pose2d(gt.poses.back());
    std::cout << "mean squared Mahalanobis distance of the increments " << mahalanobis
              << " (expected ~3); dead-reckoning error at the end " << end_error.norm() << " m, "
              << mrpt::RAD2DEG(end_error.phi()) << " deg\n";
    // E[eᵀΣ⁻¹e] = 3 plus a little from the heading drift; the mean over ~400 steps has σ ≈ 0.12.
    EXPECT_NEAR(mahalanobis, 3.05, 0.4);
    // Dead reckoning drifts visibly but stays within the building.
    EXPECT_GT(end_error.norm(), 0.05);
    EXPECT_LT(end_error.norm(), 5.0);
}
