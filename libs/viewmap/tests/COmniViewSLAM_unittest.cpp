// COmniViewSLAM end to end on the first frames of the simulated omni-views sequence (made by
// vslam-sim, shipped in datasets/omni-views): the filter against the true poses and dead
// reckoning, the views it starts and observes, reset(), determinism and bad input.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/viewmap/COmniViewSLAM.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

using mrpt_vslam::viewmap::COmniViewSLAM;

namespace {
const std::string kData = MRPT_VSLAM_SOURCE_DIR "/datasets/omni-views/rooms";
const std::string kConfig =
    MRPT_VSLAM_SOURCE_DIR "/share/mrpt-vslam/config/view-slam/omni-views.ini";

/// One frame of the sequence: the odometry increment, its covariance, the image and its time.
struct TFrame {
    mrpt::math::TPose2D u;
    Eigen::Matrix3d Q;
    mrpt::obs::CObservationImage::Ptr image;
    double t = 0;
};

std::vector<TFrame> firstFrames(size_t n)
{
    std::vector<TFrame> frames;
    mrpt_vslam::core::RawlogReader reader(kData + ".rawlog");
    for (mrpt_vslam::core::TRawlogEntry e; frames.size() < n && reader.next(e);) {
        if (!e.actions || !e.observations) continue;
        TFrame f;
        const auto [Q, u] =
            e.actions->getBestMovementEstimation()->poseChange->getCovarianceAndMean();
        f.u = u.asTPose();
        f.Q = Q.asEigen();
        f.image = e.observations->getObservationByClass<mrpt::obs::CObservationImage>();
        f.t = mrpt::Clock::toDouble(f.image->timestamp);
        frames.push_back(f);
    }
    return frames;
}

/// The filter of the shipped config, run over `frames` from the first true pose; returns the
/// position error [m] after each frame and fills the number of views and accepted observations.
std::vector<double> run(COmniViewSLAM& slam, const std::vector<TFrame>& frames,
                        const mrpt_vslam::core::TumTrajectory& truth, size_t& accepted)
{
    const auto& p0 = truth.poses.front();
    slam.reset({p0.x, p0.y, p0.yaw});
    accepted = 0;
    std::vector<double> errors;
    for (const auto& f : frames) {
        const auto r = slam.processStep(f.u, f.Q, &f.image->image, f.t);
        accepted += r.accepted();
        const int k = truth.nearestIndex(f.t, 1e-3);
        const auto x = slam.ekf().robotPose();
        errors.push_back(
            k < 0 ? NAN
                  : std::hypot(x.x - truth.poses[size_t(k)].x, x.y - truth.poses[size_t(k)].y));
    }
    return errors;
}
}  // namespace

// 25 frames (3.6 m of path): the filter stays within 0.15 m of the truth at every frame and
// ends nearer the truth than dead reckoning, having started views and observed them. Measured
// (seed 1): 0.099 m against 0.116 m at the last frame, 4 views, 52 accepted observations.
TEST(COmniViewSLAM, TracksTheSimulatedSequenceBetterThanOdometry)
{
    const auto frames = firstFrames(25);
    ASSERT_EQ(frames.size(), 25u);
    const auto truth = mrpt_vslam::core::TumTrajectory::load(kData + ".groundtruth.tum");
    const mrpt::config::CConfigFile cfg(kConfig);
    const auto slam = COmniViewSLAM::fromConfig(cfg, 1);
    size_t accepted = 0;
    const auto errors = run(*slam, frames, truth, accepted);

    mrpt::poses::CPose2D odometry(truth.poses.front().x, truth.poses.front().y,
                                  truth.poses.front().yaw);
    for (const auto& f : frames) odometry = odometry + mrpt::poses::CPose2D(f.u);
    const auto& last = truth.poses[size_t(truth.nearestIndex(frames.back().t, 1e-3))];
    const double odoError = std::hypot(odometry.x() - last.x, odometry.y() - last.y);
    for (size_t i = 0; i < errors.size(); i++) EXPECT_LT(errors[i], 0.15) << "frame " << i;
    EXPECT_LT(errors.back(), odoError);
    EXPECT_GE(slam->ekf().viewCount(), 2u);
    EXPECT_GE(accepted, 10u);
    std::printf("final error %.3f m (dead reckoning %.3f m), %zu views, %zu observations\n",
                errors.back(), odoError, slam->ekf().viewCount(), accepted);

    // reset() empties the map, and the same seed gives the same estimate again
    const auto firstPose = slam->ekf().robotPose();
    slam->reset({0, 0, 0});
    EXPECT_EQ(slam->ekf().viewCount(), 0u);
    size_t again = 0;
    run(*slam, frames, truth, again);
    EXPECT_EQ(again, accepted);
    EXPECT_EQ(slam->ekf().robotPose().x, firstPose.x);
    EXPECT_EQ(slam->ekf().robotPose().phi, firstPose.phi);
}

TEST(COmniViewSLAM, RefusesBadSteps)
{
    const mrpt::config::CConfigFile cfg(kConfig);
    const auto slam = COmniViewSLAM::fromConfig(cfg, 1);
    slam->reset({0, 0, 0});
    const Eigen::Matrix3d Q = Eigen::Matrix3d::Identity() * 1e-4;
    EXPECT_THROW(slam->processStep({NAN, 0, 0}, Q, nullptr, 0), std::invalid_argument);
    const mrpt::img::CImage empty;
    EXPECT_THROW(slam->processStep({0.1, 0, 0}, Q, &empty, 1), std::invalid_argument);
    // a refused step changed nothing; without an image only the prediction runs
    EXPECT_EQ(slam->ekf().robotPose().x, 0);
    const auto r = slam->processStep({0.1, 0, 0}, Q, nullptr, 2);
    EXPECT_EQ(r.features, 0u);
    EXPECT_NEAR(slam->ekf().robotPose().x, 0.1, 1e-12);
}
