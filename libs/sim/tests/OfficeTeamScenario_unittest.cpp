#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/vector_loadsave.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/DatasetWriter.h>
#include <mrpt_vslam/sim/OfficeTeamScenario.h>
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
#include <opencv2/imgproc.hpp>

#include "TestConfig.h"

using mrpt_vslam::test::readBytes;

namespace fs = std::filesystem;
using namespace mrpt_vslam::sim;

namespace {

constexpr int kSteps = 200;

/// The shipped office-team config, in memory so tests can change keys.
mrpt::config::CConfigFileMemory shippedConfig()
{
    std::vector<std::string> lines;
    mrpt::io::loadTextFile(lines, test::officeTeamIni());
    return mrpt::config::CConfigFileMemory(lines);
}

/// The shipped scenario, loaded once.
const OfficeTeamScenario& shipped()
{
    static const OfficeTeamScenario scenario = [] {
        OfficeTeamScenario s;
        s.loadConfig(test::officeTeamConfig());
        return s;
    }();
    return scenario;
}

/// The world of the shipped scenario, built once.
const TOfficeModel& shippedModel()
{
    static const TOfficeModel model = shipped().world.build(shipped().textures);
    return model;
}

/// Runs the shipped scenario into a fresh directory; returns the output prefix.
std::string runTeam(const std::string& dir_name, uint64_t seed, int robots, int frames, bool images,
                    OfficeTeamScenario* scenario_out = nullptr)
{
    const fs::path dir = mrpt_vslam::test::processScratchFolder() / dir_name;
    fs::remove_all(dir);
    OfficeTeamScenario scenario;
    scenario.loadConfig(test::officeTeamConfig());
    TSimulationOptions opts;
    opts.out_prefix = (dir / "office").string();
    opts.seed = seed;
    opts.robots = robots;
    opts.frames = frames;
    opts.write_images = images;
    const TSimulationSummary s = scenario.run(opts);
    EXPECT_EQ(s.frames, frames < 0 ? kSteps : frames);
    EXPECT_EQ(s.robots, robots);
    if (scenario_out) *scenario_out = scenario;
    return opts.out_prefix;
}

mrpt::poses::CPose3D leftCamera(const mrpt::math::TPose2D& robot)
{
    return mrpt::poses::CPose3D(mrpt::poses::CPose2D(robot)) + shipped().camera_on_robot;
}

}  // namespace

TEST(OfficeTeamScenario, PathsStartAsInThePaperAndStayInFreeSpace)
{
    const OfficeTeamScenario& s = shipped();
    ASSERT_EQ(s.trajectories.size(), 3u);
    const auto paths = s.paths(3, kSteps);
    EXPECT_EQ(paths[0].front(), mrpt::math::TPose2D(0, 0, 0));
    EXPECT_EQ(paths[1].front(), mrpt::math::TPose2D(-4, 0, 0));
    const double axis_yaw = 0;  // the shipped camera looks along the robot's x axis
    double min_clearance = 1e9, min_ahead = 1e9, max_step = 0, max_turn = 0;
    for (const auto& path : paths) {
        ASSERT_EQ(path.size(), static_cast<size_t>(kSteps));
        for (size_t k = 0; k < path.size(); k++) {
            min_clearance = std::min(min_clearance, s.world.clearance(path[k].x, path[k].y));
            const mrpt::poses::CPose3D cam = leftCamera(path[k]);
            min_ahead = std::min(min_ahead, s.world.distanceAhead(cam.x(), cam.y(),
                                                                  path[k].phi + axis_yaw, cam.z()));
            if (k == 0) continue;
            max_step = std::max(max_step,
                                std::hypot(path[k].x - path[k - 1].x, path[k].y - path[k - 1].y));
            max_turn =
                std::max(max_turn, std::abs(mrpt::math::wrapToPi(path[k].phi - path[k - 1].phi)));
        }
    }
    std::cout << "min clearance " << min_clearance << " m, min distance ahead " << min_ahead
              << " m, max step " << max_step << " m, max turn " << mrpt::RAD2DEG(max_turn)
              << " deg\n";
    EXPECT_GE(min_clearance, 0.6);  // Pioneer P3-AT: ~0.35 m radius
    EXPECT_GE(min_ahead, 1.0);
    EXPECT_LE(max_step, 0.25);
    EXPECT_LE(max_turn, mrpt::DEG2RAD(12.0));
    // The robots never meet: at least 2 m apart at every step.
    for (size_t a = 0; a < 3; a++)
        for (size_t b = a + 1; b < 3; b++)
            for (size_t k = 0; k < static_cast<size_t>(kSteps); k++)
                ASSERT_GE(std::hypot(paths[a][k].x - paths[b][k].x, paths[a][k].y - paths[b][k].y),
                          2.0)
                    << "R" << a + 1 << " and R" << b + 1 << " at step " << k;
}

TEST(OfficeTeamScenario, EveryRobotClosesALoop)
{
    const auto paths = shipped().paths(3, kSteps);
    for (size_t r = 0; r < paths.size(); r++) {
        // Back within 0.3 m of an earlier pose, heading within 20°, after 60 steps or more.
        bool loop = false;
        for (size_t b = 60; b < paths[r].size() && !loop; b++)
            for (size_t a = 0; a + 60 <= b && !loop; a++)
                loop = std::hypot(paths[r][b].x - paths[r][a].x, paths[r][b].y - paths[r][a].y) <
                           0.3 &&
                       std::abs(mrpt::math::wrapToPi(paths[r][b].phi - paths[r][a].phi)) <
                           mrpt::DEG2RAD(20.0);
        EXPECT_TRUE(loop) << "R" << r + 1;
    }
}

TEST(OfficeTeamScenario, EveryFrameSeesTexturedFacesOverMostOfTheImage)
{
    const OfficeTeamScenario& s = shipped();
    const TOfficeModel& m = shippedModel();
    const auto paths = s.paths(3, kSteps);
    double min_vertical = 1, min_hit = 1;
    size_t min_corners = 100000;
    for (const auto& path : paths) {
        for (size_t k = 0; k < path.size(); k += 4) {
            const mrpt::poses::CPose3D cam = leftCamera(path[k]);
            const TRenderedView v = s.stereo.renderView(m.scene, cam);
            size_t hit = 0, vertical = 0;
            for (int f : v.face) {
                hit += f >= 0;
                vertical += f >= 0 && m.scene.rectangles[static_cast<size_t>(f)].isVertical();
            }
            min_hit = std::min(min_hit, static_cast<double>(hit) / v.face.size());
            min_vertical = std::min(min_vertical, static_cast<double>(vertical) / v.face.size());
            size_t corners = 0;
            for (const TCornerLandmark& c : m.corners)
                corners += s.stereo.seesPoint(m.scene, cam, c.position, 3);
            min_corners = std::min(min_corners, corners);
        }
    }
    std::cout << "over the frames: at least " << 100 * min_vertical
              << " % of the pixels on walls and furniture, " << min_corners
              << " ground-truth corners in view\n";
    EXPECT_EQ(min_hit, 1.0) << "inside the room every ray hits a face";
    EXPECT_GE(min_vertical, 0.4);
    EXPECT_GE(min_corners, 6u);
}

TEST(OfficeTeamScenario, GroundTruthCornersAppearWhereTheCameraModelPutsThem)
{
    // cv::cornerSubPix (7 × 7 px window) started 0.57 px away from the projection of each
    // ground-truth corner that is within 3.5 m, has its whole window on its own face (no
    // occlusion edge) and no other corner within 6 px; where the window holds other structure
    // it wanders off or gives up (stays at the start), so the test looks at the distribution.
    const OfficeTeamScenario& s = shipped();
    const TOfficeModel& m = shippedModel();
    StereoRenderer cam = s.stereo;
    cam.reset(21);
    constexpr int kWin = 3;
    std::vector<double> errors;
    for (const auto& path : s.paths(2, kSteps)) {
        for (size_t k = 0; k < path.size(); k += 12) {
            const mrpt::poses::CPose3D left = leftCamera(path[k]);
            const auto [image, unused] = cam.render(m.scene, left);
            const TRenderedView view = cam.renderView(m.scene, left);
            std::vector<Eigen::Vector2d> in_view;
            std::vector<const TCornerLandmark*> candidates;
            for (const TCornerLandmark& c : m.corners) {
                if (!cam.seesPoint(m.scene, left, c.position, 8)) continue;
                const auto p = left.inverseComposePoint(
                    mrpt::math::TPoint3D(c.position.x(), c.position.y(), c.position.z()));
                in_view.push_back(cam.project({p.x, p.y, p.z}));
                if (p.z <= 3.5) candidates.push_back(&c);
            }
            std::vector<cv::Point2f> expected, found;
            for (const TCornerLandmark* c : candidates) {
                const auto p = left.inverseComposePoint(
                    mrpt::math::TPoint3D(c->position.x(), c->position.y(), c->position.z()));
                const Eigen::Vector2d uv = cam.project({p.x, p.y, p.z});
                const auto near = std::count_if(in_view.begin(), in_view.end(),
                                                [&](const auto& o) { return (o - uv).norm() < 6; });
                bool own_face = true;
                const int u0 = static_cast<int>(std::lround(uv.x())),
                          v0 = static_cast<int>(std::lround(uv.y()));
                for (int dv = -kWin - 1; dv <= kWin + 1; dv++)
                    for (int du = -kWin - 1; du <= kWin + 1; du++)
                        own_face =
                            own_face &&
                            view.face[static_cast<size_t>((v0 + dv) * cam.width + u0 + du)] ==
                                static_cast<int>(c->face);
                if (near > 1 || !own_face) continue;
                expected.emplace_back(static_cast<float>(uv.x()), static_cast<float>(uv.y()));
                found.push_back(expected.back() + cv::Point2f(0.4f, -0.4f));
            }
            if (found.empty()) continue;
            cv::cornerSubPix(
                image.asCvMatRef(), found, cv::Size(kWin, kWin), cv::Size(-1, -1),
                cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-3));
            for (size_t i = 0; i < found.size(); i++)
                errors.push_back(cv::norm(found[i] - expected[i]));
        }
    }
    ASSERT_GE(errors.size(), 300u);
    std::sort(errors.begin(), errors.end());
    const double median = errors[errors.size() / 2];
    const double within =
        static_cast<double>(std::lower_bound(errors.begin(), errors.end(), 0.5) - errors.begin()) /
        errors.size();
    std::cout << errors.size() << " corners: median " << median << " px, " << 100 * within
              << " % within 0.5 px\n";
    EXPECT_LT(median, 0.3);
    EXPECT_GE(within, 0.75);
}

TEST(OfficeTeamScenario, SameSeedGivesByteIdenticalFiles)
{
    const std::string a = runTeam("seed1a", 1, 2, 5, true), b = runTeam("seed1b", 1, 2, 5, true);
    std::vector<std::string> files{".rawlog",          ".groundtruth_R1.tum", ".groundtruth_R2.tum",
                                   ".odometry_R1.tum", ".odometry_R2.tum",    ".landmarks.txt",
                                   ".topview.png"};
    for (const std::string r : {"R1", "R2"})
        for (int k = 0; k < 5; k++)
            for (const std::string side : {"_L", "_R"})
                files.push_back("_Images/" + DatasetWriter::imageFileName(r + "_STEREO", k, side));
    for (const std::string& f : files) {
        ASSERT_TRUE(fs::exists(a + f)) << f;
        EXPECT_EQ(readBytes(a + f), readBytes(b + f)) << f;
    }
    EXPECT_FALSE(fs::exists(a + ".rawlog.tmp"));

    const std::string c = runTeam("seed2", 2, 2, 5, true);
    EXPECT_NE(readBytes(a + ".rawlog"), readBytes(c + ".rawlog"));
    EXPECT_NE(readBytes(a + ".odometry_R2.tum"), readBytes(c + ".odometry_R2.tum"));
    EXPECT_NE(readBytes(a + "_Images/R1_STEREO_000003_L.png"),
              readBytes(c + "_Images/R1_STEREO_000003_L.png"));
    // The world and the paths do not depend on the seed.
    EXPECT_EQ(readBytes(a + ".groundtruth_R2.tum"), readBytes(c + ".groundtruth_R2.tum"));
    EXPECT_EQ(readBytes(a + ".landmarks.txt"), readBytes(c + ".landmarks.txt"));
}

TEST(OfficeTeamScenario, RawlogHoldsOdometryStereoAndGroundTruthPerRobotAndStep)
{
    constexpr int kFrames = 4;
    const std::string prefix = runTeam("readback", 1, 2, kFrames, true);
    const OfficeTeamScenario& s = shipped();
    const auto gt = mrpt_vslam::core::TumTrajectory::load(prefix + ".groundtruth_R2.tum");
    ASSERT_EQ(gt.size(), static_cast<size_t>(kFrames));
    const auto landmarks = mrpt_vslam::core::LandmarkFile::load(prefix + ".landmarks.txt");
    EXPECT_EQ(landmarks.size(), shippedModel().corners.size());

    mrpt::img::CImage::setImagesPathBase(prefix + "_Images");
    mrpt::io::CFileGZInputStream in(prefix + ".rawlog");
    auto ar = mrpt::serialization::archiveFrom(in);
    mrpt::obs::CActionCollection::Ptr acts;
    mrpt::obs::CSensoryFrame::Ptr sf;
    mrpt::obs::CObservation::Ptr obs;
    size_t index = 0;
    std::vector<mrpt::obs::CObservation::Ptr> all;
    while (mrpt::obs::CRawlog::getActionObservationPairOrObservation(ar, acts, sf, obs, index)) {
        ASSERT_TRUE(obs) << "observation-only rawlog";
        all.push_back(obs);
    }
    const std::vector<std::string> order{"R1_ODOM", "R1_STEREO", "R1_GROUND_TRUTH",
                                         "R2_ODOM", "R2_STEREO", "R2_GROUND_TRUTH"};
    ASSERT_EQ(all.size(), order.size() * kFrames);
    for (size_t i = 0; i < all.size(); i++) {
        const size_t step = i / order.size();
        EXPECT_EQ(all[i]->sensorLabel, order[i % order.size()]);
        EXPECT_DOUBLE_EQ(mrpt::Clock::toDouble(all[i]->timestamp),
                         s.start_time + static_cast<double>(step) * 1.0);
    }
    // R2's first odometry is its true start pose; ground truth matches the TUM file.
    auto odo = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(all[3]);
    ASSERT_TRUE(odo);
    EXPECT_EQ(odo->odometry, mrpt::poses::CPose2D(-4, 0, 0));
    auto truth = std::dynamic_pointer_cast<mrpt::obs::CObservationRobotPose>(all[11]);
    ASSERT_TRUE(truth);
    EXPECT_NEAR(truth->pose.mean.x(), gt.poses[1].x, 1e-6);
    EXPECT_NEAR(mrpt::Clock::toDouble(truth->timestamp), gt.timestamps[1], 1e-6);

    auto stereo = std::dynamic_pointer_cast<mrpt::obs::CObservationStereoImages>(all[10]);
    ASSERT_TRUE(stereo);
    EXPECT_TRUE(stereo->areImagesRectified());
    EXPECT_TRUE(stereo->hasImageRight);
    EXPECT_FALSE(stereo->hasImageDisparity);
    EXPECT_EQ(stereo->leftCamera.fx(), 280);
    EXPECT_EQ(stereo->leftCamera.cx(), 159.5);
    EXPECT_EQ(stereo->rightCameraPose.x(), 0.12);
    EXPECT_LT((mrpt::poses::CPose3D(stereo->cameraPose)
                   .getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>()
                   .asEigen() -
               s.camera_on_robot.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>().asEigen())
                  .cwiseAbs()
                  .maxCoeff(),
              1e-12);
    EXPECT_EQ(stereo->imageLeft.getExternalStorageFile(), "R2_STEREO_000001_L.png");
    EXPECT_EQ(stereo->imageRight.getExternalStorageFile(), "R2_STEREO_000001_R.png");
    // The external images load through MRPT: 320×240 gray, and differ (parallax, noise).
    EXPECT_EQ(stereo->imageLeft.getWidth(), 320u);
    EXPECT_EQ(stereo->imageRight.getHeight(), 240u);
    EXPECT_FALSE(stereo->imageLeft.isColor());
    EXPECT_GT(
        cv::norm(stereo->imageLeft.asCvMatRef(), stereo->imageRight.asCvMatRef(), cv::NORM_L1),
        0.0);
}

TEST(OfficeTeamScenario, OdometryOfEachRobotFollowsTheConfiguredNoiseIndependently)
{
    const std::string three = runTeam("odo3", 5, 3, -1, false);
    const std::string two = runTeam("odo2", 5, 2, -1, false);
    // Each robot has its own streams: a third robot changes nothing for R1 and R2.
    EXPECT_EQ(readBytes(two + ".odometry_R1.tum"), readBytes(three + ".odometry_R1.tum"));
    EXPECT_EQ(readBytes(two + ".odometry_R2.tum"), readBytes(three + ".odometry_R2.tum"));
    EXPECT_FALSE(fs::exists(two + "_Images"));

    const OdometrySimulator& model = shipped().odometry;
    std::vector<std::vector<double>> normalised_x(3);
    double mahalanobis = 0;
    size_t count = 0;
    for (int r = 0; r < 3; r++) {
        const std::string name = "R" + std::to_string(r + 1);
        const auto gt =
            mrpt_vslam::core::TumTrajectory::load(three + ".groundtruth_" + name + ".tum");
        const auto odo =
            mrpt_vslam::core::TumTrajectory::load(three + ".odometry_" + name + ".tum");
        ASSERT_EQ(gt.size(), static_cast<size_t>(kSteps));
        ASSERT_EQ(odo.timestamps, gt.timestamps);
        EXPECT_EQ(odo.poses.front(), gt.poses.front()) << "starts at the true pose";
        for (size_t k = 1; k < gt.size(); k++) {
            const auto pose2d = [](const mrpt::math::TPose3D& p) {
                return mrpt::poses::CPose2D(p.x, p.y, p.yaw);
            };
            const mrpt::poses::CPose2D truth = pose2d(gt.poses[k]) - pose2d(gt.poses[k - 1]);
            const mrpt::poses::CPose2D noisy = pose2d(odo.poses[k]) - pose2d(odo.poses[k - 1]);
            mrpt::obs::CActionRobotMovement2D a;
            a.computeFromOdometry(truth, model.motionModel());
            mrpt::math::CMatrixDouble33 cov;
            mrpt::poses::CPose2D mean;
            a.poseChange->getCovarianceAndMean(cov, mean);
            const Eigen::Vector3d e(noisy.x() - truth.x(), noisy.y() - truth.y(),
                                    mrpt::math::wrapToPi(noisy.phi() - truth.phi()));
            mahalanobis += e.dot(cov.asEigen().inverse() * e);
            count++;
            normalised_x[static_cast<size_t>(r)].push_back(e.x() / std::sqrt(cov(0, 0)));
        }
    }
    // E[eᵀΣ⁻¹e] = 3 (plus ~0.05 from the heading drift); its mean over 597 steps has σ ≈ 0.1.
    EXPECT_NEAR(mahalanobis / count, 3.05, 0.35);
    const auto correlation = [](const std::vector<double>& a, const std::vector<double>& b) {
        double sa = 0, sb = 0, sab = 0, saa = 0, sbb = 0;
        const double n = static_cast<double>(a.size());
        for (size_t i = 0; i < a.size(); i++) {
            sa += a[i], sb += b[i], sab += a[i] * b[i], saa += a[i] * a[i], sbb += b[i] * b[i];
        }
        return (sab - sa * sb / n) / std::sqrt((saa - sa * sa / n) * (sbb - sb * sb / n));
    };
    // 199 independent pairs: |ρ| has σ ≈ 0.07.
    EXPECT_LT(std::abs(correlation(normalised_x[0], normalised_x[1])), 0.25);
    EXPECT_LT(std::abs(correlation(normalised_x[0], normalised_x[2])), 0.25);
    EXPECT_LT(std::abs(correlation(normalised_x[1], normalised_x[2])), 0.25);
}

TEST(OfficeTeamScenario, RobotsSeeTheSameCornersFromDifferentPlaces)
{
    OfficeTeamScenario s;
    runTeam("overlap", 1, 2, -1, false, &s);
    const TTeamStatistics& st = s.statistics();
    std::cout << st.corners << " corners; seen by R1 " << st.seen[0] << ", R2 " << st.seen[1]
              << "; tracked over 3 frames by R1 " << st.tracked[0] << ", R2 " << st.tracked[1]
              << ", by both " << st.tracked_by_several << "\n";
    EXPECT_EQ(st.corners, shippedModel().corners.size());
    for (size_t r = 0; r < 2; r++) {
        EXPECT_GE(st.tracked[r], st.corners / 2) << "R" << r + 1;
        EXPECT_LE(st.tracked[r], st.seen[r]);
        EXPECT_GT(st.path_length[r], 30.0);
    }
    EXPECT_GE(st.tracked_by_several, st.corners / 3);
}

TEST(OfficeTeamScenario, SmallerTeamRemovesTheFilesOfTheRobotsItDropped)
{
    const std::string prefix = runTeam("shrink", 1, 3, 2, true);
    ASSERT_TRUE(fs::exists(prefix + ".odometry_R3.tum"));
    ASSERT_TRUE(fs::exists(prefix + "_Images/R3_STEREO_000001_L.png"));
    OfficeTeamScenario s;
    s.loadConfig(test::officeTeamConfig());
    TSimulationOptions opts;
    opts.out_prefix = prefix;
    opts.robots = 2;
    opts.frames = 2;
    s.run(opts);
    EXPECT_TRUE(fs::exists(prefix + ".odometry_R2.tum"));
    EXPECT_FALSE(fs::exists(prefix + ".odometry_R3.tum"));
    EXPECT_FALSE(fs::exists(prefix + ".groundtruth_R3.tum"));
    EXPECT_FALSE(fs::exists(prefix + "_Images/R3_STEREO_000001_L.png"));
    EXPECT_TRUE(fs::exists(prefix + "_Images/R2_STEREO_000001_L.png"));
}

TEST(OfficeTeamScenario, TeamSizeMustFitTheTrajectorySections)
{
    for (int robots : {1, 4}) {
        OfficeTeamScenario s;
        s.loadConfig(test::officeTeamConfig());
        TSimulationOptions opts;
        opts.out_prefix = (mrpt_vslam::test::processScratchFolder() / "bad" / "x").string();
        opts.robots = robots;
        try {
            s.run(opts);
            FAIL() << "no exception for " << robots << " robots";
        } catch (const mrpt_vslam::core::UsageError& e) {
            EXPECT_NE(std::string(e.what()).find("--robots must be 2 to 3"), std::string::npos)
                << e.what();
        }
        EXPECT_FALSE(fs::exists(opts.out_prefix + ".rawlog"));
    }
    EXPECT_EQ(createScenario("office-team")->name(), "office-team");
}

TEST(OfficeTeamScenario, PathsThroughFurnitureOrFacingWallsFailNamingTheSection)
{
    const auto error = [](const std::string& section, const std::string& key,
                          const std::string& value) {
        mrpt::config::CConfigFileMemory cfg = shippedConfig();
        cfg.write(section, key, value);
        OfficeTeamScenario s;
        try {
            s.loadConfig(cfg);
        } catch (const mrpt_vslam::core::UsageError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    // R2 turns north into the shelf on the west island's south face (x -2.5 .. -1, y 1.12 ..).
    const std::string through = error("Trajectory_R2", "waypoints", "-1.75 0  -1.75 3");
    EXPECT_NE(through.find("[Trajectory_R2] waypoints: frame"), std::string::npos) << through;
    EXPECT_NE(through.find("[Robots] "), std::string::npos) << through;
    // R1 stops 0.5 m in front of the east wall (its camera 0.4 m), looking at it.
    const std::string facing = error("Trajectory_R1", "waypoints", "10.5 0");
    EXPECT_NE(facing.find("[Trajectory_R1] waypoints: frame"), std::string::npos) << facing;
    EXPECT_NE(facing.find("min_view_distance"), std::string::npos) << facing;
    EXPECT_NE(error("Trajectory_R3", "frames", "150").find("[Trajectory_R3] frames"),
              std::string::npos);
    EXPECT_NE(error("StereoCamera", "baseline", "0").find("[StereoCamera] baseline"),
              std::string::npos);
}
