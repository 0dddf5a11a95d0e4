#include <gtest/gtest.h>
#include <mrpt/math/CMatrixDynamic.h>
#include <mrpt/math/CVectorFixed.h>
#include <mrpt/math/num_jacobian.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/multirobot/StereoGeometry.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>

using mrpt_vslam::multirobot::StereoGeometry;
using mrpt_vslam::multirobot::TStereoPixel;
using mrpt_vslam::multirobot::TStereoPixelNoise;

namespace {

// fx ≠ fy so that the f_x/f_y factor of Y is exercised.
const StereoGeometry kGeometry(420.0, 400.0, 321.5, 238.25, 0.12);

mrpt::obs::CObservationStereoImages rectifiedPair()
{
    mrpt::obs::CObservationStereoImages obs;
    mrpt::img::TStereoCamera params;
    params.leftCamera.setIntrinsicParamsFromValues(420, 400, 321.5, 238.25);
    params.rightCamera = params.leftCamera;
    params.rightCameraPose = mrpt::math::TPose3DQuat(0.12, 0, 0, 1, 0, 0, 0);
    obs.setStereoCameraParams(params);
    return obs;
}

}  // namespace

TEST(StereoGeometry, TriangulatesEq12WithYDown)
{
    // Eq. 12 with f_x: Z = f_x B / d, X = B (c − c_x) / d, Y = B (f_x/f_y)(r − c_y) / d
    const TStereoPixel px{300.25, 400.5, 21.0};
    const auto p = kGeometry.triangulate(px);
    EXPECT_NEAR(p.z, 420 * 0.12 / 21.0, 1e-12);
    EXPECT_NEAR(p.x, 0.12 * (400.5 - 321.5) / 21.0, 1e-12);
    EXPECT_NEAR(p.y, 0.12 * (420.0 / 400.0) * (300.25 - 238.25) / 21.0, 1e-12);
    // A pixel below the principal point is below the optical axis: y > 0 (down); Eq. 12's Y
    // (up) is its negative.
    EXPECT_GT(p.y, 0);
    const StereoGeometry square(400, 400, 320, 240, 0.1);
    const auto q = square.triangulate({250, 330, 8});
    EXPECT_NEAR(-q.y, 0.1 * (240 - 250) / 8.0, 1e-12);  // Y_Eq.12 = I (C_y − r) / d
    EXPECT_NEAR(q.x, 0.1 * (330 - 320) / 8.0, 1e-12);
    EXPECT_NEAR(q.z, 400 * 0.1 / 8.0, 1e-12);
}

TEST(StereoGeometry, JacobianMatchesCentralDifferences)
{
    using Vec3 = mrpt::math::CVectorFixedDouble<3>;
    const std::function<void(const Vec3&, const int&, Vec3&)> f = [](const Vec3& drc, const int&,
                                                                     Vec3& out) {
        const auto p = kGeometry.triangulate({drc[1], drc[2], drc[0]});
        out[0] = p.x;
        out[1] = p.y;
        out[2] = p.z;
    };
    for (const TStereoPixel px : {TStereoPixel{10.0, 620.0, 3.5}, TStereoPixel{238.0, 321.0, 60.0},
                                  TStereoPixel{470.5, 5.25, 17.75}}) {
        Vec3 x;
        x[0] = px.disparity;
        x[1] = px.row;
        x[2] = px.col;
        Vec3 h;
        h.fill(1e-4);
        mrpt::math::CMatrixDouble numeric;
        mrpt::math::estimateJacobian(x, f, h, 0, numeric);
        const auto J = kGeometry.jacobian(px);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                EXPECT_NEAR(J(i, j), numeric(i, j), 1e-7 * (1 + std::abs(J(i, j))))
                    << "J(" << i << "," << j << ") at d = " << px.disparity;
    }
}

TEST(StereoGeometry, ProjectInvertsTriangulate)
{
    auto& rng = mrpt::random::getRandomGenerator();
    rng.randomize(3);
    for (int k = 0; k < 1000; k++) {
        const TStereoPixel px{rng.drawUniform(0, 480), rng.drawUniform(0, 640),
                              rng.drawUniform(0.5, 128)};
        const TStereoPixel back = kGeometry.project(kGeometry.triangulate(px));
        EXPECT_NEAR(back.row, px.row, 1e-9);
        EXPECT_NEAR(back.col, px.col, 1e-9);
        EXPECT_NEAR(back.disparity, px.disparity, 1e-9);

        const mrpt::math::TPoint3D p(rng.drawUniform(-3, 3), rng.drawUniform(-2, 2),
                                     rng.drawUniform(0.2, 15));
        const auto q = kGeometry.triangulate(kGeometry.project(p));
        EXPECT_NEAR(q.x, p.x, 1e-9);
        EXPECT_NEAR(q.y, p.y, 1e-9);
        EXPECT_NEAR(q.z, p.z, 1e-9);
    }
    EXPECT_THROW(kGeometry.project({0, 0, -1}), std::invalid_argument);
    EXPECT_THROW(kGeometry.triangulate({10, 10, 0}), std::invalid_argument);
    EXPECT_THROW(kGeometry.triangulate({10, std::nan(""), 5}), std::invalid_argument);
}

TEST(StereoGeometry, CovarianceMatchesMonteCarloAtShortRange)
{
    // d = 60 px → Z = 0.84 m: σ_d / d = 1.7 %, where first-order propagation holds.
    const TStereoPixel px{150.0, 420.0, 60.0};
    const TStereoPixelNoise noise = TStereoPixelNoise::paper();
    const auto R = kGeometry.covariance(px, noise);

    auto& rng = mrpt::random::getRandomGenerator();
    rng.randomize(11);
    const int n = 200000;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (int k = 0; k < n; k++) {
        const TStereoPixel noisy{
            px.row + noise.sigma_row * rng.drawGaussian1D_normalized(),
            px.col + noise.sigma_col * rng.drawGaussian1D_normalized(),
            px.disparity + noise.sigma_disparity * rng.drawGaussian1D_normalized()};
        const auto p = kGeometry.triangulate(noisy);
        const Eigen::Vector3d v(p.x, p.y, p.z);
        mean += v;
        second += v * v.transpose();
    }
    mean /= n;
    const Eigen::Matrix3d sample = second / n - mean * mean.transpose();
    for (int i = 0; i < 3; i++) {
        // variances within 3 %, correlations within 0.02
        EXPECT_NEAR(sample(i, i) / R(i, i), 1.0, 0.03) << "axis " << i;
        for (int j = 0; j < i; j++)
            EXPECT_NEAR(sample(i, j) / std::sqrt(sample(i, i) * sample(j, j)),
                        R(i, j) / std::sqrt(R(i, i) * R(j, j)), 0.02)
                << i << "," << j;
    }
    // R_t = J R_sp Jᵀ exactly
    const auto Jm = kGeometry.jacobian(px);
    const Eigen::Matrix3d J = Jm.asEigen();
    const Eigen::Matrix3d expected = J * Eigen::Vector3d(1, 100, 100).asDiagonal() * J.transpose();
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) EXPECT_NEAR(R(i, j), expected(i, j), 1e-15);
}

TEST(StereoGeometry, FromObservationReadsARectifiedPair)
{
    const StereoGeometry g = StereoGeometry::fromObservation(rectifiedPair());
    EXPECT_DOUBLE_EQ(g.fx(), 420);
    EXPECT_DOUBLE_EQ(g.fy(), 400);
    EXPECT_DOUBLE_EQ(g.cx(), 321.5);
    EXPECT_DOUBLE_EQ(g.cy(), 238.25);
    EXPECT_DOUBLE_EQ(g.baseline(), 0.12);
    EXPECT_DOUBLE_EQ(g.disparityOffset(), 0);
    EXPECT_EQ(StereoGeometry::whyNotRectified(rectifiedPair()), "");
}

// A pair rectified with the principal points' columns apart (MRPT's rawlog-edit --stereo-rectify
// without --rectify-centers-coincide): the offset is taken off the columns' difference, so a
// point projected into both images triangulates back to itself.
TEST(StereoGeometry, ARightPrincipalPointOffsetShiftsTheDisparity)
{
    auto obs = rectifiedPair();
    obs.rightCamera.setIntrinsicParamsFromValues(420, 400, 314.8, 238.25);
    const StereoGeometry g = StereoGeometry::fromObservation(obs);
    EXPECT_NEAR(g.disparityOffset(), 321.5 - 314.8, 1e-12);
    const mrpt::math::TPoint3D point(0.4, -0.2, 3.1);
    // the point's columns in each image, from each camera's own intrinsics
    const double col_left = 321.5 + 420 * point.x / point.z;
    const double col_right = 314.8 + 420 * (point.x - 0.12) / point.z;
    const auto p = g.triangulate(
        {238.25 + 400 * point.y / point.z, col_left, col_left - col_right - g.disparityOffset()});
    EXPECT_NEAR(p.x, point.x, 1e-12);
    EXPECT_NEAR(p.y, point.y, 1e-12);
    EXPECT_NEAR(p.z, point.z, 1e-12);
}

TEST(StereoGeometry, FromObservationRejectsPairsThatAreNotRectified)
{
    const auto expectError = [](const mrpt::obs::CObservationStereoImages& obs,
                                const std::string& text) {
        try {
            StereoGeometry::fromObservation(obs);
            ADD_FAILURE() << "no exception; expected: " << text;
        } catch (const std::invalid_argument& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(text), std::string::npos) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    };
    auto obs = rectifiedPair();
    obs.leftCamera.dist[0] = -0.2;
    expectError(obs, "not rectified: the left camera has non-zero distortion");
    obs = rectifiedPair();
    obs.rightCamera.dist[3] = 0.001;
    expectError(obs, "not rectified: the right camera has non-zero distortion");
    obs = rectifiedPair();
    obs.leftCamera.distortion = mrpt::img::DistortionModel::kannala_brandt;
    expectError(obs, "kannala_brandt");
    obs = rectifiedPair();
    obs.rightCamera.setIntrinsicParamsFromValues(420, 400, 321.5, 240);
    expectError(obs, "left and right intrinsics differ");
    EXPECT_EQ(StereoGeometry::whyNotRectified(obs), "left and right intrinsics differ (fx fy cy)");
    obs = rectifiedPair();
    obs.rightCameraPose = mrpt::poses::CPose3DQuat(mrpt::poses::CPose3D(0.12, 0, 0, 0.01, 0, 0));
    expectError(obs, "right camera is rotated by 0.57");
    obs = rectifiedPair();
    obs.rightCameraPose = mrpt::poses::CPose3DQuat(mrpt::poses::CPose3D(0.12, 0.01, 0, 0, 0, 0));
    expectError(obs, "off the left camera's x axis");
    obs = rectifiedPair();
    obs.rightCameraPose = mrpt::poses::CPose3DQuat(mrpt::poses::CPose3D(-0.12, 0, 0, 0, 0, 0));
    expectError(obs, "must be at +x");
    obs = rectifiedPair();
    obs.leftCamera.setIntrinsicParamsFromValues(std::nan(""), 400, 321.5, 238.25);
    expectError(obs, "not finite");
    obs = rectifiedPair();
    obs.leftCamera.dist[1] = std::numeric_limits<double>::infinity();
    expectError(obs, "non-finite distortion");
    obs = rectifiedPair();  // distorted, as a pair that would be rectified, with f_x < 0
    obs.leftCamera.setIntrinsicParamsFromValues(-420, 400, 321.5, 238.25);
    obs.rightCamera = obs.leftCamera;
    obs.leftCamera.dist[0] = obs.rightCamera.dist[0] = -0.2;
    expectError(obs, "focal lengths must be positive");

    EXPECT_THROW(StereoGeometry(400, 400, 320, 240, 0), std::invalid_argument);
    EXPECT_THROW(StereoGeometry(-400, 400, 320, 240, 0.1), std::invalid_argument);
    EXPECT_THROW(StereoGeometry(400, 400, std::nan(""), 240, 0.1), std::invalid_argument);
}
