#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/multirobot/StereoFrontEnd.h>
#include <mrpt_vslam/test/UnrectifiedStereoPair.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>

#include "StereoTestScene.h"

using mrpt_vslam::multirobot::StereoFrontEnd;
using mrpt_vslam::multirobot::test::TPlaneScene;

namespace {

struct TDepthErrors {
    size_t count = 0;
    double rms_rel = 0;  ///< RMS of (Z − Z_true) / Z_true
    double max_rel = 0;  ///< largest |Z − Z_true| / Z_true
};

/// Depth errors of the points of the last frame against the plane seen from `position`.
TDepthErrors depthErrors(const StereoFrontEnd& fe, const TPlaneScene& scene,
                         const Eigen::Vector3d& position)
{
    TDepthErrors e;
    double sum2 = 0;
    for (const auto& p : fe.points()) {
        const double z_true = scene.pointAt(p.pixel.row, p.pixel.col, position).z();
        const double rel = (p.point.z - z_true) / z_true;
        sum2 += rel * rel;
        e.max_rel = std::max(e.max_rel, std::abs(rel));
        e.count++;
    }
    e.rms_rel = e.count ? std::sqrt(sum2 / e.count) : 0;
    return e;
}

/// A camera moving along +x by `step` metres per frame.
Eigen::Vector3d positionOf(int frame, double step = 0.05) { return {step * frame, 0, 0}; }

}  // namespace

TEST(StereoFrontEnd, PointsLieOnAFrontoParallelPlaneAt2m)
{
    const TPlaneScene scene = TPlaneScene::plane(2.0, 0.0);
    StereoFrontEnd fe({});
    fe.process(*scene.stereo(positionOf(0)));
    const TDepthErrors e = depthErrors(fe, scene, positionOf(0));
    // 320 × 240, f = 400 px, B = 0.12 m: d = 24 px at 2 m
    EXPECT_GE(e.count, 60u);  // measured 92 of 97 corners
    // measured: RMS 0.17 %, max 0.50 % (disparity RMS 0.04 px)
    EXPECT_LT(e.rms_rel, 0.004) << "max " << e.max_rel;
    EXPECT_LT(e.max_rel, 0.015);
    for (const auto& p : fe.points()) {
        // the lateral coordinates follow from the same pixel: checked through the ray
        const Eigen::Vector3d truth = scene.pointAt(p.pixel.row, p.pixel.col, positionOf(0));
        EXPECT_NEAR(p.point.x / p.point.z, truth.x() / truth.z(), 1e-9);
        EXPECT_NEAR(p.point.y / p.point.z, truth.y() / truth.z(), 1e-9);
    }
}

TEST(StereoFrontEnd, PointsLieOnASlantedPlane)
{
    // Turned by 35° about the vertical axis: depth from about 1.6 m to 2.7 m across the image
    // and foreshortened, differently warped patches in the two images.
    const TPlaneScene scene = TPlaneScene::plane(2.0, 35 * M_PI / 180);
    StereoFrontEnd fe({});
    fe.process(*scene.stereo(positionOf(0)));
    const TDepthErrors e = depthErrors(fe, scene, positionOf(0));
    EXPECT_GE(e.count, 60u);  // measured 100 of 101 corners
    // measured: RMS 0.28 %, max 0.67 % (disparity RMS 0.06 px)
    EXPECT_LT(e.rms_rel, 0.006) << "max " << e.max_rel;
    EXPECT_LT(e.max_rel, 0.02);
}

TEST(StereoFrontEnd, CovarianceIsConsistentWithTheErrors)
{
    // Three frames of a plane turned by 20°, about 290 points. The truth is taken at the same
    // left pixel, so the error of a point is its disparity error, along the viewing ray.
    const TPlaneScene scene = TPlaneScene::plane(2.0, 20 * M_PI / 180);
    struct TSample {
        Eigen::Vector3d truth, err;
        Eigen::Matrix3d R;
    };
    const auto samples = [&](const StereoFrontEnd::TOptions& opts) {
        std::vector<TSample> out;
        StereoFrontEnd fe(opts);
        for (int frame = 0; frame < 3; frame++) {
            fe.process(*scene.stereo(positionOf(frame), 2.0, 100 + frame));
            for (const auto& p : fe.points()) {
                const Eigen::Vector3d truth =
                    scene.pointAt(p.pixel.row, p.pixel.col, positionOf(frame));
                out.push_back({truth, Eigen::Vector3d(p.point.x, p.point.y, p.point.z) - truth,
                               p.cov.asEigen()});
            }
        }
        return out;
    };

    // 1. The paper's R_t (σ_d = 1 px, σ_r = σ_c = 10 px) is depth-dominant at 2 m and
    //    conservative for this sub-pixel matcher: NEES along its main axis ε²/λ_max has a mean
    //    far below 1 (measured 0.002) and no point beyond the χ²₁ 99.9 % bound.
    StereoFrontEnd::TOptions paper_options;
    paper_options.pixel_noise = mrpt_vslam::multirobot::TStereoPixelNoise::paper();
    const auto paper = samples(paper_options);
    ASSERT_GE(paper.size(), 250u);
    double sum = 0, worst = 0;
    for (const TSample& s : paper) {
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(s.R);
        const Eigen::Vector3d axis = eig.eigenvectors().col(2);
        EXPECT_GT(std::abs(axis.dot(s.truth.normalized())), 0.95);  // along the ray
        const double along = axis.dot(s.err);
        const double nees = along * along / eig.eigenvalues()(2);
        sum += nees;
        worst = std::max(worst, nees);
    }
    EXPECT_LT(sum / paper.size(), 0.05);
    EXPECT_LT(worst, 10.83);

    // 2. With σ_d = 0.05 px (the disparity RMS this matcher reaches, doc/stereo-frontend.md)
    //    and negligible pixel-position noise, R_t predicts the 3D errors: the mean NEES
    //    εᵀ R_t⁻¹ ε of the one-dimensional error is 1 (measured 0.91).
    StereoFrontEnd::TOptions tight;
    tight.pixel_noise = {0.05, 0.01, 0.01};
    const auto matched = samples(tight);
    sum = 0;
    for (const TSample& s : matched) sum += s.err.dot(s.R.ldlt().solve(s.err));
    EXPECT_GT(sum / matched.size(), 0.5);
    EXPECT_LT(sum / matched.size(), 2.0);
}

TEST(StereoFrontEnd, EmitsOnlyFromTheThirdFrameAndKeepsTrackIds)
{
    const TPlaneScene scene = TPlaneScene::plane(2.0, 0.0);
    StereoFrontEnd fe({});                                         // min_track_length = 3, no cap
    std::map<int64_t, std::vector<Eigen::Vector3d>> world_points;  // per track id
    std::map<int64_t, uint32_t> last_length;
    std::vector<size_t> emitted;
    size_t continued = 0, exact = 0;
    for (int frame = 0; frame < 5; frame++) {
        const auto obs = scene.stereo(positionOf(frame), 2.0, frame + 1);
        const std::vector<StereoFrontEnd::TPoint> previous = fe.points();
        const auto lm = fe.process(*obs);
        emitted.push_back(lm->landmarks.landmarks.size());

        // Every continued track moved with the camera: −f·0.05/2 = −10 px, same row. Harris
        // maxima on curved blob edges may wander by a few pixels; a wrong association would
        // jump by at least the corner spacing (10 px).
        for (const auto& p : fe.points()) {
            if (p.track_length < 2) continue;
            const auto prev = std::find_if(previous.begin(), previous.end(),
                                           [&](const auto& q) { return q.track_id == p.track_id; });
            ASSERT_NE(prev, previous.end());
            EXPECT_EQ(prev->track_length + 1, p.track_length);
            const double dc = p.pixel.col - prev->pixel.col, dr = p.pixel.row - prev->pixel.row;
            EXPECT_LT(std::hypot(dc + 10, dr), 5.0) << "track " << p.track_id;
            continued++;
            exact += std::abs(dc + 10) <= 1 && std::abs(dr) <= 1;
        }
        for (size_t i = 0; i < lm->landmarks.landmarks.size(); i++) {
            const auto* l = lm->landmarks.landmarks.get(i);
            EXPECT_GE(l->seenTimesCount, 3u);
            EXPECT_LE(l->seenTimesCount, static_cast<uint32_t>(frame + 1));
            if (last_length.count(l->ID)) {
                EXPECT_EQ(l->seenTimesCount, last_length[l->ID] + 1);
            }
            last_length[l->ID] = l->seenTimesCount;
            const auto& m = l->pose_mean;
            world_points[l->ID].push_back(positionOf(frame) + Eigen::Vector3d(m.x, m.y, m.z));
        }
    }
    EXPECT_GE(exact, continued * 95 / 100);
    EXPECT_EQ(emitted[0], 0u);
    EXPECT_EQ(emitted[1], 0u);
    EXPECT_GE(emitted[2], 40u);
    EXPECT_GE(emitted[3], emitted[2] * 8 / 10);
    EXPECT_GE(emitted[4], emitted[2] * 7 / 10);
    // The same id is the same physical point: its world position agrees over the frames
    // (σ_Z = Z²σ_d/(fB) ≈ 0.08 m for σ_d = 1 px; the matcher does 5× better).
    size_t seen_thrice = 0;
    for (const auto& [id, pts] : world_points) {
        for (const auto& p : pts) EXPECT_LT((p - pts.front()).norm(), 0.05) << "track " << id;
        seen_thrice += pts.size() == 3;
    }
    EXPECT_GE(seen_thrice, emitted[2] * 7 / 10);
}

TEST(StereoFrontEnd, PerFrameCapKeepsTheLongestThenNearestTracks)
{
    // Slanted plane so that depths differ; frames 0-3 give tracks of lengths 1 to 4.
    const TPlaneScene scene = TPlaneScene::plane(2.0, 35 * M_PI / 180);
    StereoFrontEnd::TOptions opts;
    opts.max_landmarks_per_frame = 6;
    StereoFrontEnd fe(opts);
    for (int frame = 0; frame < 4; frame++) {
        const auto lm = fe.process(*scene.stereo(positionOf(frame, 0.03), 2.0, frame + 1));
        const auto& stats = fe.lastFrameStats();
        EXPECT_EQ(stats.emitted, std::min<size_t>(stats.eligible, 6));
        EXPECT_EQ(lm->landmarks.landmarks.size(), stats.emitted);
        if (frame < 2) continue;
        ASSERT_GT(stats.eligible, 6u) << "frame " << frame;

        // Nothing left out is longer, or as long and nearer, than something emitted.
        std::vector<std::pair<uint32_t, double>> out;  // (length, Z) of the emitted ones
        for (size_t i = 0; i < lm->landmarks.landmarks.size(); i++) {
            const auto* l = lm->landmarks.landmarks.get(i);
            out.emplace_back(l->seenTimesCount, l->pose_mean.z);
        }
        for (const auto& p : fe.points()) {
            if (p.track_length < 3) continue;
            const bool is_emitted = std::any_of(out.begin(), out.end(), [&](const auto& o) {
                return o.first == p.track_length && o.second == p.point.z;
            });
            if (is_emitted) continue;
            for (const auto& [length, z] : out) {
                EXPECT_GE(length, p.track_length);
                if (length == p.track_length) {
                    EXPECT_LE(z, p.point.z);
                }
            }
        }
        if (frame == 3) {
            for (const auto& o : out) EXPECT_EQ(o.first, 4u);
        }
    }
}

TEST(StereoFrontEnd, BrightnessChangeOfTheRightImageKeepsTheMatches)
{
    const TPlaneScene scene = TPlaneScene::plane(2.0, 20 * M_PI / 180);
    const auto obs = scene.stereo(positionOf(0));
    StereoFrontEnd plain({}), changed({});
    plain.process(*obs);
    const size_t n_plain = plain.points().size();

    cv::Mat right = obs->imageRight.asCvMat<cv::Mat>(mrpt::img::DEEP_COPY), darker;
    right.convertTo(darker, CV_8U, 0.6, 45);  // gain 0.6, offset +45 gray levels
    obs->imageRight = mrpt::img::CImage(darker, mrpt::img::DEEP_COPY);
    changed.process(*obs);
    EXPECT_GE(changed.points().size(), n_plain * 9 / 10);
    const TDepthErrors e = depthErrors(changed, scene, positionOf(0));
    EXPECT_LT(e.rms_rel, 0.01);
    EXPECT_LT(e.max_rel, 0.03);
}

TEST(StereoFrontEnd, OutputObservationCarriesTheLandmarks)
{
    const TPlaneScene scene = TPlaneScene::plane(2.0, 0.0);
    StereoFrontEnd::TOptions opts;
    opts.min_track_length = 1;
    StereoFrontEnd fe(opts);
    const auto obs = scene.stereo(positionOf(0));
    obs->sensorLabel = "R7_STEREO";
    const auto lm = fe.process(*obs);

    EXPECT_EQ(lm->sensorLabel, "R7_LANDMARKS");
    EXPECT_EQ(lm->timestamp, obs->timestamp);
    EXPECT_EQ(lm->refCameraPose, mrpt::poses::CPose3D(obs->cameraPose));
    ASSERT_EQ(lm->landmarks.landmarks.size(), fe.points().size());
    ASSERT_GT(fe.points().size(), 0u);
    for (size_t i = 0; i < fe.points().size(); i++) {
        const auto& p = fe.points()[i];
        const mrpt::maps::CLandmark* l = lm->landmarks.landmarks.getByID(p.track_id);
        ASSERT_NE(l, nullptr);
        EXPECT_EQ(l->pose_mean, p.point);
        EXPECT_FLOAT_EQ(l->pose_cov_11, p.cov(0, 0));
        EXPECT_FLOAT_EQ(l->pose_cov_22, p.cov(1, 1));
        EXPECT_FLOAT_EQ(l->pose_cov_33, p.cov(2, 2));
        EXPECT_FLOAT_EQ(l->pose_cov_12, p.cov(0, 1));
        EXPECT_FLOAT_EQ(l->pose_cov_13, p.cov(0, 2));
        EXPECT_FLOAT_EQ(l->pose_cov_23, p.cov(1, 2));
        EXPECT_EQ(l->seenTimesCount, 1u);
        EXPECT_EQ(l->timestampLastSeen, obs->timestamp);
        ASSERT_EQ(l->features.size(), 1u);
        const auto& f = l->features[0];
        EXPECT_EQ(f.type, mrpt::vision::featHarris);
        EXPECT_EQ(f.keypoint.pt.x, static_cast<float>(p.pixel.col));
        EXPECT_EQ(f.keypoint.pt.y, static_cast<float>(p.pixel.row));
        EXPECT_EQ(f.keypoint.ID, static_cast<mrpt::vision::TFeatureID>(p.track_id));
        ASSERT_TRUE(f.descriptors.SURF.has_value());
        ASSERT_EQ(f.descriptors.SURF->size(), 64u);
        for (size_t k = 0; k < 64; k++) EXPECT_EQ((*f.descriptors.SURF)[k], p.descriptor[k]);
    }
    EXPECT_EQ(StereoFrontEnd::landmarksLabel("R2_STEREO"), "R2_LANDMARKS");
    EXPECT_EQ(StereoFrontEnd::landmarksLabel("CAM"), "CAM_LANDMARKS");
    EXPECT_EQ(StereoFrontEnd::landmarksLabel("STEREO_R1"), "STEREO_R1_LANDMARKS");
}

TEST(StereoFrontEnd, ObservationSerializesAndReadsBack)
{
    const TPlaneScene scene = TPlaneScene::plane(2.0, 0.0);
    StereoFrontEnd::TOptions opts;
    opts.min_track_length = 1;
    StereoFrontEnd fe(opts);
    const auto lm = fe.process(*scene.stereo(positionOf(0)));
    ASSERT_GT(lm->landmarks.landmarks.size(), 10u);

    mrpt::io::CMemoryStream buf;
    mrpt::serialization::archiveFrom(buf) << *lm;
    buf.Seek(0);
    const auto obj = mrpt::serialization::archiveFrom(buf).ReadObject();
    const auto back = std::dynamic_pointer_cast<mrpt::obs::CObservationVisualLandmarks>(obj);
    ASSERT_TRUE(back);
    EXPECT_EQ(back->sensorLabel, lm->sensorLabel);
    EXPECT_EQ(back->timestamp, lm->timestamp);
    EXPECT_EQ(back->refCameraPose, lm->refCameraPose);
    ASSERT_EQ(back->landmarks.landmarks.size(), lm->landmarks.landmarks.size());
    for (size_t i = 0; i < lm->landmarks.landmarks.size(); i++) {
        const auto* a = lm->landmarks.landmarks.get(i);
        const auto* b = back->landmarks.landmarks.get(i);
        EXPECT_EQ(b->ID, a->ID);
        EXPECT_EQ(b->pose_mean, a->pose_mean);
        EXPECT_EQ(b->pose_cov_11, a->pose_cov_11);
        EXPECT_EQ(b->pose_cov_23, a->pose_cov_23);
        EXPECT_EQ(b->seenTimesCount, a->seenTimesCount);
        EXPECT_EQ(b->timestampLastSeen, a->timestampLastSeen);
        ASSERT_EQ(b->features.size(), 1u);
        EXPECT_EQ(b->features[0].keypoint.pt.x, a->features[0].keypoint.pt.x);
        EXPECT_EQ(b->features[0].keypoint.pt.y, a->features[0].keypoint.pt.y);
        EXPECT_EQ(b->features[0].keypoint.ID, a->features[0].keypoint.ID);
        EXPECT_EQ(b->features[0].type, mrpt::vision::featHarris);
        ASSERT_TRUE(b->features[0].descriptors.SURF.has_value());
        EXPECT_EQ(*b->features[0].descriptors.SURF, *a->features[0].descriptors.SURF);
    }
}

TEST(StereoFrontEnd, BadInputThrowsOneLineAndKeepsTheTracks)
{
    const TPlaneScene scene = TPlaneScene::plane(2.0, 0.0);
    StereoFrontEnd fe({});
    fe.process(*scene.stereo(positionOf(0)));
    const auto expectError = [&](const mrpt::obs::CObservationStereoImages& obs,
                                 const std::string& text) {
        try {
            fe.process(obs);
            ADD_FAILURE() << "no exception; expected: " << text;
        } catch (const std::exception& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(text), std::string::npos) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    };
    const auto good = scene.stereo(positionOf(1));
    auto bad = *good;
    bad.hasImageRight = false;
    expectError(bad, "no right image");
    bad = *good;
    bad.imageLeft = mrpt::img::CImage();
    expectError(bad, "left image is empty");
    bad = *good;
    bad.imageRight =
        mrpt::img::CImage(cv::Mat(240, 321, CV_8UC1, cv::Scalar(0)), mrpt::img::DEEP_COPY);
    expectError(bad, "images are 321x240 but the calibration is for 320x240");
    bad = *good;
    bad.leftCamera.distortion = mrpt::img::DistortionModel::kannala_brandt;
    expectError(bad, "kannala_brandt (fisheye) model, which is not read");
    bad = *good;
    bad.rightCameraPose = mrpt::poses::CPose3DQuat(mrpt::poses::CPose3D(-0.12, 0, 0, 0, 0.05, 0));
    expectError(bad, "must be at +x of the left one");
    bad = *good;
    bad.leftCamera.setIntrinsicParamsFromValues(std::nan(""), 400, 159.5, 119.5);
    bad.rightCamera = bad.leftCamera;
    expectError(bad, "not finite");
    bad = *good;
    bad.cameraPose = mrpt::poses::CPose3DQuat(
        mrpt::poses::CPose3D(std::numeric_limits<double>::infinity(), 0, 0, 0, 0, 0));
    expectError(bad, "camera pose on the robot is not finite");
    bad = *good;
    bad.leftCamera.ncols = bad.rightCamera.ncols = 640;
    expectError(bad, "images are 320x240 but the calibration is for 640x240");
    bad = *good;
    bad.imageLeft =
        mrpt::img::CImage(cv::Mat(240, 320, CV_16UC1, cv::Scalar(0)), mrpt::img::DEEP_COPY);
    expectError(bad, "8-bit");

    // The failed frames did not touch the tracks: the good one continues them.
    fe.process(*good);
    EXPECT_GE(fe.lastFrameStats().tracked, fe.lastFrameStats().points * 8 / 10);
    EXPECT_GT(fe.lastFrameStats().points, 50u);
}

// A head with barrel distortion whose right camera is turned inwards by 1 deg and tilted by
// 4 deg, before a fronto-parallel plane 2 m away: the pair is rectified, and its points, carried
// by the rectified camera's pose back into the stated camera's frame, lie on the plane. The
// rectified camera is turned by R1ᵀ of the stated one; turned by R1 (as CStereoRectifyMap::
// rectify(CObservationStereoImages&) turns it), the points would lie on a plane tilted by 4 deg.
// Measured: 83 points, depth RMS 0.18 %, max 0.47 % (turned by R1: RMS 0.95 %, max 1.96 %).
TEST(StereoFrontEnd, AHeadThatIsNotRectifiedIsRectifiedWithItsPose)
{
    const TPlaneScene scene = TPlaneScene::plane(2.0, 0.0);
    const auto rectified = scene.stereo(positionOf(0));
    const auto obs = mrpt_vslam::test::unrectifiedPair(
        *rectified, -0.2, 0.05,
        mrpt::poses::CPose3D(0, 0, 0, 0, mrpt::DEG2RAD(-1.0), mrpt::DEG2RAD(4.0)));
    ASSERT_FALSE(mrpt_vslam::multirobot::StereoGeometry::whyNotRectified(obs).empty());
    StereoFrontEnd fe({});
    const auto out = fe.process(obs);
    EXPECT_EQ(fe.lastFrameStats().rectified, 1u);
    EXPECT_FALSE(fe.lastFrameStats().rectified_because.empty());
    const mrpt::poses::CPose3D stated(obs.cameraPose), used(out->refCameraPose);
    size_t n = 0;
    double sum2 = 0, max_rel = 0;
    for (const auto& p : fe.points()) {
        const auto in_stated = stated.inverseComposePoint(used.composePoint(p.point));
        const double rel = (in_stated.z - 2.0) / 2.0;
        sum2 += rel * rel;
        max_rel = std::max(max_rel, std::abs(rel));
        n++;
    }
    const double rms = n ? std::sqrt(sum2 / n) : 0;
    std::printf("%zu points, depth RMS %.2f %%, max %.2f %%\n", n, 100 * rms, 100 * max_rel);
    EXPECT_GE(n, 40u);
    EXPECT_LT(rms, 0.005);
    EXPECT_LT(max_rel, 0.012);
}

TEST(StereoFrontEnd, WhyNoLandmarksNamesTheStepThatLostThePoints)
{
    const TPlaneScene scene = TPlaneScene::plane(2.0, 0.0);
    // The counts of several frames add up; three frames of a plane at 2 m emit landmarks.
    StereoFrontEnd fe({});
    StereoFrontEnd::TFrameStats sum;
    size_t corners = 0, emitted = 0;
    for (int frame = 0; frame < 3; frame++) {
        fe.process(*scene.stereo(positionOf(frame)));
        sum += fe.lastFrameStats();
        corners += fe.lastFrameStats().corners;
        emitted += fe.lastFrameStats().emitted;
        if (frame < 2) {
            EXPECT_NE(StereoFrontEnd::whyNoLandmarks(sum, fe.options()).find("(step 5"),
                      std::string::npos)
                << "frame " << frame;
        }
    }
    EXPECT_EQ(sum.frames, 3u);
    EXPECT_EQ(sum.rectified, 0u);
    EXPECT_EQ(sum.corners, corners);
    EXPECT_EQ(sum.emitted, emitted);
    EXPECT_GT(emitted, 0u);
    EXPECT_EQ(StereoFrontEnd::whyNoLandmarks(sum, fe.options()), "");
    EXPECT_NEAR(sum.nearest_match, 2.0, 0.03);
    EXPECT_NEAR(sum.farthest_match, 2.0, 0.03);

    const auto why = [&](mrpt::obs::CObservationStereoImages obs, StereoFrontEnd::TOptions o) {
        StereoFrontEnd one(o);
        one.process(obs);
        return StereoFrontEnd::whyNoLandmarks(one.lastFrameStats(), o);
    };
    const auto good = scene.stereo(positionOf(0));
    const mrpt::img::CImage blank(cv::Mat(240, 320, CV_8UC1, cv::Scalar(128)),
                                  mrpt::img::DEEP_COPY);
    auto obs = *good;
    obs.imageLeft = blank;
    EXPECT_NE(why(obs, {}).find("no Harris corner in the left images (step 1"), std::string::npos)
        << why(obs, {});
    obs = *good;
    obs.imageRight = blank;
    EXPECT_NE(why(obs, {}).find("corners matched along its row of the right image (step 2"),
              std::string::npos)
        << why(obs, {});
    StereoFrontEnd::TOptions far;
    far.min_depth = 5;
    far.max_depth = 10;
    const std::string depth = why(*good, far);
    EXPECT_NE(depth.find("min_depth, max_depth = 5, 10 m: they lie at 1.9"), std::string::npos)
        << depth;
    EXPECT_NE(depth.find("(step 2"), std::string::npos) << depth;
}

TEST(StereoFrontEnd, ColourImagesGiveTheGrayscaleResult)
{
    const TPlaneScene scene = TPlaneScene::plane(2.0, 0.0);
    const auto gray = scene.stereo(positionOf(0));
    auto colour = *gray;
    for (auto* img : {&colour.imageLeft, &colour.imageRight}) {
        cv::Mat c;
        cv::cvtColor(img->asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY), c, cv::COLOR_GRAY2BGR);
        *img = mrpt::img::CImage(c, mrpt::img::DEEP_COPY);
    }
    StereoFrontEnd a({}), b({});
    a.process(*gray);
    b.process(colour);
    ASSERT_EQ(a.points().size(), b.points().size());
    for (size_t i = 0; i < a.points().size(); i++)
        EXPECT_EQ(a.points()[i].pixel.disparity, b.points()[i].pixel.disparity);
}

TEST(StereoFrontEnd, OptionsLoadValidateAndRoundTrip)
{
    const auto loadError = [](const std::string& text) -> std::string {
        mrpt::config::CConfigFileMemory cfg("[StereoFrontEnd]\n" + text + "\n");
        StereoFrontEnd::TOptions o;
        try {
            o.loadFromConfigFile(cfg, "StereoFrontEnd");
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(loadError("max_depth = 0.2"),
              "[StereoFrontEnd] max_depth: must be finite and > min_depth");
    EXPECT_EQ(loadError("max_corners = 0"), "[StereoFrontEnd] max_corners: must be >= 1");
    EXPECT_EQ(loadError("harris_quality = 1"),
              "[StereoFrontEnd] harris_quality: must be in (0, 1)");
    EXPECT_EQ(loadError("harris_k = -0.1"), "[StereoFrontEnd] harris_k: must be in (0, 0.25)");
    EXPECT_EQ(loadError("harris_block_size = 1"),
              "[StereoFrontEnd] harris_block_size: must be >= 2");
    EXPECT_EQ(loadError("sigma_disparity = 0"), "[StereoFrontEnd] sigma_disparity: must be > 0");
    EXPECT_EQ(loadError("sigma_row = nan"), "[StereoFrontEnd] sigma_row: must be > 0");
    EXPECT_EQ(loadError("usurf_scale = -2"), "[StereoFrontEnd] usurf_scale: must be > 0");
    EXPECT_EQ(loadError("track_ratio = 1.5"), "[StereoFrontEnd] track_ratio: must be in (0, 1]");
    EXPECT_EQ(loadError("min_track_length = 0"), "[StereoFrontEnd] min_track_length: must be >= 1");
    EXPECT_EQ(loadError("max_landmarks_per_frame = -1"),
              "[StereoFrontEnd] max_landmarks_per_frame: must be >= 0 (0 = no limit)");
    EXPECT_EQ(loadError("ncc_window = 4"),
              "[StereoFrontEnd] ncc_window: must be odd, from 3 to 51");
    EXPECT_EQ(loadError("max_landmarks_per_frame = 8\nmin_track_length = 3"), "");

    // The sigmas measured best (doc/multirobot.md), and the paper's track length, are the defaults.
    const StereoFrontEnd::TOptions defaults;
    EXPECT_EQ(defaults.pixel_noise.sigma_disparity, 0.5);
    EXPECT_EQ(defaults.pixel_noise.sigma_row, 3.0);
    EXPECT_EQ(defaults.pixel_noise.sigma_col, 3.0);
    EXPECT_EQ(defaults.min_track_length, 3);

    // save → load gives the same options
    StereoFrontEnd::TOptions changed;
    changed.max_corners = 123;
    changed.matching.ncc_window = 9;
    changed.matching.left_right_check = false;
    changed.pixel_noise.sigma_col = 4.5;
    changed.track_ratio = 0.65;
    mrpt::config::CConfigFileMemory saved;
    changed.saveToConfigFile(saved, "StereoFrontEnd");
    StereoFrontEnd::TOptions loaded;
    // MRPT keeps the padded key names in memory: reparse the text as a file would be
    loaded.loadFromConfigFile(mrpt::config::CConfigFileMemory(saved.getContent()),
                              "StereoFrontEnd");
    mrpt::config::CConfigFileMemory again;
    loaded.saveToConfigFile(again, "StereoFrontEnd");
    EXPECT_EQ(again.getContent(), saved.getContent());
    EXPECT_EQ(loaded.max_corners, 123);
    EXPECT_EQ(loaded.matching.ncc_window, 9);
    EXPECT_FALSE(loaded.matching.left_right_check);
    EXPECT_EQ(loaded.pixel_noise.sigma_col, 4.5);
}

TEST(StereoFrontEnd, ShippedConfigDocumentsEveryKeyWithItsDefault)
{
    mrpt_vslam::core::CheckedConfigFile cfg;
    cfg.loadFile(MRPT_VSLAM_SOURCE_DIR
                 "/share/mrpt-vslam/config/multirobot-vslam/stereo-frontend.ini");
    StereoFrontEnd::TOptions shipped;
    shipped.loadFromConfigFile(cfg, "StereoFrontEnd");
    EXPECT_NO_THROW(cfg.throwIfUnreadKeys());  // nothing else in the file

    const StereoFrontEnd::TOptions defaults;
    mrpt::config::CConfigFileMemory defaults_text, shipped_text;
    defaults.saveToConfigFile(defaults_text, "StereoFrontEnd");
    shipped.saveToConfigFile(shipped_text, "StereoFrontEnd");
    EXPECT_EQ(shipped_text.getContent(), defaults_text.getContent());
    // every key the options read is written in the file
    std::vector<std::string> keys;
    mrpt::config::CConfigFileMemory(defaults_text.getContent()).getAllKeys("StereoFrontEnd", keys);
    EXPECT_EQ(keys.size(), 22u);
    for (const std::string& key : keys)
        EXPECT_NE(cfg.read_string("StereoFrontEnd", key, "<missing>"), "<missing>") << key;
}
