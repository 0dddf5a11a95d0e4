#include <gtest/gtest.h>
#include <mrpt/math/CVectorFixed.h>
#include <mrpt/math/num_jacobian.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/omni_fastslam/BearingMeasurementModel.h>

#include <cmath>

using mrpt::math::TPose2D;
using mrpt_vslam::omni_fastslam::BearingMeasurementModel;

namespace {

using Vec3 = mrpt::math::CVectorFixedDouble<3>;
using Vec2 = mrpt::math::CVectorFixedDouble<2>;

Vec3 vec3(double a, double b, double c)
{
    Vec3 v;
    v[0] = a;
    v[1] = b;
    v[2] = c;
    return v;
}

struct TJacobianCase {
    const BearingMeasurementModel* model;
    TPose2D robot;
    Eigen::Vector3d landmark;
    Eigen::Vector2d z0;  ///< nominal prediction: outputs are wrapped differences from it
};

/// Numerical ∂h/∂x (wrt_pose) or ∂h/∂m of the wrapped prediction.
Eigen::Matrix<double, 2, 3> numericJacobian(const TJacobianCase& c, bool wrt_pose)
{
    const Vec3 x0 = wrt_pose ? vec3(c.robot.x, c.robot.y, c.robot.phi)
                             : vec3(c.landmark.x(), c.landmark.y(), c.landmark.z());
    const std::function<void(const Vec3&, const TJacobianCase&, Vec2&)> f =
        [wrt_pose](const Vec3& x, const TJacobianCase& cc, Vec2& out) {
            const TPose2D robot = wrt_pose ? TPose2D(x[0], x[1], x[2]) : cc.robot;
            const Eigen::Vector3d m = wrt_pose ? cc.landmark : Eigen::Vector3d(x[0], x[1], x[2]);
            const Eigen::Vector2d d =
                BearingMeasurementModel::innovation(cc.model->predict(m, robot), cc.z0);
            out[0] = d[0];
            out[1] = d[1];
        };
    const Vec3 increments = vec3(1e-6, 1e-6, 1e-6);
    mrpt::math::CMatrixDouble J;
    mrpt::math::estimateJacobian(x0, f, increments, c, J);
    return J.asEigen();
}

void expectJacobiansMatch(const BearingMeasurementModel& model, const TPose2D& robot,
                          const Eigen::Vector3d& landmark)
{
    const auto pred = model.predictWithJacobians(landmark, robot);
    ASSERT_TRUE(pred.valid);
    const TJacobianCase c{&model, robot, landmark, pred.z};
    const auto Hx_num = numericJacobian(c, true);
    const auto Hm_num = numericJacobian(c, false);
    const double scale = 1.0 + pred.H_x.cwiseAbs().maxCoeff() + pred.H_m.cwiseAbs().maxCoeff();
    EXPECT_LT((pred.H_x - Hx_num).cwiseAbs().maxCoeff(), 1e-5 * scale) << "H_x\n"
                                                                       << pred.H_x << "\nnumeric\n"
                                                                       << Hx_num;
    EXPECT_LT((pred.H_m - Hm_num).cwiseAbs().maxCoeff(), 1e-5 * scale) << "H_m\n"
                                                                       << pred.H_m << "\nnumeric\n"
                                                                       << Hm_num;
}

}  // namespace

TEST(BearingMeasurementModel, PredictsClosedFormAngles)
{
    const BearingMeasurementModel model;  // camera at (0, 0, 1.8), axes of the robot
    const TPose2D robot(1, 2, 0);
    // 3 m ahead and 3 m above the camera: φ = 0, θ = 45°
    auto z = model.predict({4, 2, 4.8}, robot);
    EXPECT_NEAR(z[0], 0, 1e-12);
    EXPECT_NEAR(z[1], M_PI / 4, 1e-12);
    // Robot turned 90°: a light towards map −x is on the camera's +y side (φ = +90°)
    z = model.predict({-2, 2, 4.8}, TPose2D(1, 2, M_PI / 2));
    EXPECT_NEAR(z[0], M_PI / 2, 1e-12);
    EXPECT_NEAR(z[1], M_PI / 4, 1e-12);
    // Straight above: θ = 0
    EXPECT_NEAR(model.predict({1, 2, 7}, robot)[1], 0, 1e-12);
    // Light behind and below the horizon of a camera offset by 0.5 m forward
    const BearingMeasurementModel offset(mrpt::poses::CPose3D(0.5, 0, 1.8, 0, 0, 0));
    z = offset.predict({0.5 - 1, 0, 1.8 - 1}, TPose2D(0, 0, 0));
    EXPECT_NEAR(std::abs(z[0]), M_PI, 1e-12);
    EXPECT_NEAR(z[1], 3 * M_PI / 4, 1e-12);
}

TEST(BearingMeasurementModel, JacobiansMatchNumericalEstimate)
{
    auto& rng = mrpt::random::getRandomGenerator();
    rng.randomize(1234);
    for (int i = 0; i < 200; i++) {
        const mrpt::poses::CPose3D sensor(rng.drawUniform(-0.3, 0.3), rng.drawUniform(-0.3, 0.3),
                                          rng.drawUniform(1.0, 2.0), rng.drawUniform(-M_PI, M_PI),
                                          rng.drawUniform(-0.2, 0.2), rng.drawUniform(-0.2, 0.2));
        const BearingMeasurementModel model(sensor);
        const TPose2D robot(rng.drawUniform(-10, 10), rng.drawUniform(-10, 10),
                            rng.drawUniform(-M_PI, M_PI));
        const Eigen::Vector3d light(rng.drawUniform(-15, 15), rng.drawUniform(-15, 15),
                                    rng.drawUniform(3, 8));
        expectJacobiansMatch(model, robot, light);
    }
}

TEST(BearingMeasurementModel, JacobiansMatchNearZenithAndAzimuthPi)
{
    const BearingMeasurementModel model;
    const TPose2D robot(0.5, -1.0, 0.3);
    const Eigen::Vector3d camera = model.rayOriginInMap(robot);
    // 1 cm off the optical axis, 5 m up: θ ≈ 2 mrad, |∂φ/∂m| ≈ 100 rad/m
    expectJacobiansMatch(model, robot,
                         camera + Eigen::Vector3d(0.01 * std::cos(1.0), 0.01 * std::sin(1.0), 5));
    // azimuth just either side of ±π in the camera frame
    for (const double eps : {-1e-4, 1e-4}) {
        const double phi = M_PI + eps + robot.phi;  // camera axes follow the robot yaw
        const Eigen::Vector3d light =
            camera + Eigen::Vector3d(4 * std::cos(phi), 4 * std::sin(phi), 3);
        const auto pred = model.predictWithJacobians(light, robot);
        EXPECT_GT(std::abs(pred.z[0]), M_PI - 2e-4);
        expectJacobiansMatch(model, robot, light);
    }
}

TEST(BearingMeasurementModel, RayDirectionInvertsPrediction)
{
    const BearingMeasurementModel model(mrpt::poses::CPose3D(0.2, -0.1, 1.6, 0.4, 0.05, -0.03));
    const TPose2D robot(3, -2, 2.5);
    const Eigen::Vector3d light(1, 4, 6.5);
    const Eigen::Vector2d z = model.predict(light, robot);
    const Eigen::Vector3d dir = model.rayDirectionInMap(z, robot);
    const Eigen::Vector3d expected = (light - model.rayOriginInMap(robot)).normalized();
    EXPECT_NEAR(dir.norm(), 1.0, 1e-12);
    EXPECT_LT((dir - expected).norm(), 1e-12);
    // directionOfAngles / anglesOfDirection round trip
    const Eigen::Vector2d angles(-2.9, 1.1);
    const Eigen::Vector2d back = BearingMeasurementModel::anglesOfDirection(
        BearingMeasurementModel::directionOfAngles(angles));
    EXPECT_NEAR(back[0], angles[0], 1e-12);
    EXPECT_NEAR(back[1], angles[1], 1e-12);
}

TEST(BearingMeasurementModel, InnovationWrapsAzimuth)
{
    const auto d = BearingMeasurementModel::innovation({M_PI - 0.1, 0.5}, {-M_PI + 0.1, 0.4});
    EXPECT_NEAR(d[0], -0.2, 1e-12);
    EXPECT_NEAR(d[1], 0.1, 1e-12);
    const auto e = BearingMeasurementModel::innovation({-M_PI + 0.1, 0.5}, {M_PI - 0.1, 0.5});
    EXPECT_NEAR(e[0], 0.2, 1e-12);
    // exactly ±π maps to +π: the range is (−π, π]
    EXPECT_DOUBLE_EQ(BearingMeasurementModel::innovation({0, 0}, {M_PI, 0})[0], M_PI);
    EXPECT_DOUBLE_EQ(BearingMeasurementModel::innovation({-M_PI, 0}, {0, 0})[0], M_PI);
}

TEST(BearingMeasurementModel, YawPitchFollowMrptConvention)
{
    // MRPT bearing observations: yaw = azimuth, pitch = −elevation
    const double elevation = 0.6, yaw = -2.0;
    const auto z = BearingMeasurementModel::anglesOfYawPitch(yaw, -elevation);
    EXPECT_NEAR(z[0], yaw, 1e-12);
    EXPECT_NEAR(z[1], M_PI / 2 - elevation, 1e-12);
    const Eigen::Vector3d dir = BearingMeasurementModel::directionOfAngles(z);
    EXPECT_NEAR(std::asin(dir.z()), elevation, 1e-12);
    EXPECT_NEAR(std::atan2(dir.y(), dir.x()), yaw, 1e-12);
}
