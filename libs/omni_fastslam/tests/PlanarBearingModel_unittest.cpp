// The planar (azimuth-only) measurement model and the geometry of its cross-points
// (doc/omni-fastslam.md §12, Eq. P1-P3).
#include <gtest/gtest.h>
#include <mrpt/math/CVectorFixed.h>
#include <mrpt/math/num_jacobian.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/omni_fastslam/BearingMeasurementModel.h>
#include <mrpt_vslam/omni_fastslam/RayCrossPoint.h>

#include <cmath>

using Eigen::Vector2d;
using Eigen::Vector3d;
using mrpt::math::TPose2D;
using mrpt_vslam::omni_fastslam::BearingMeasurementModel;
using mrpt_vslam::omni_fastslam::TCrossPointLimits;
using mrpt_vslam::omni_fastslam::TMeasurementModelKind;

namespace {

constexpr double kDeg = M_PI / 180;

BearingMeasurementModel planarModel(double x = 0, double y = 0, double yaw = 0)
{
    return BearingMeasurementModel(mrpt::poses::CPose3D(x, y, 0.3, yaw, 0, 0),
                                   TMeasurementModelKind::Planar);
}

TCrossPointLimits limitsOf(double min_angle, double max_range, bool planar, double min_range = 0)
{
    TCrossPointLimits limits;
    limits.min_angle = min_angle;
    limits.max_range = max_range;
    limits.planar = planar;
    limits.min_range = min_range;
    return limits;
}

/// φ wrapped to (−π, π], as the model wraps innovations
double wrap(double a) { return BearingMeasurementModel::innovation({a, 0}, {0, 0})[0]; }

/// The Jacobian of the wrapped azimuth w.r.t. the robot pose (wrt_pose) or the landmark (x, y, z),
/// by mrpt::math::estimateJacobian around the nominal prediction.
Eigen::RowVector3d numericAzimuthJacobian(const BearingMeasurementModel& model,
                                          const TPose2D& robot, const Vector3d& landmark,
                                          bool wrt_pose)
{
    using Vec3 = mrpt::math::CVectorFixedDouble<3>;
    using Vec1 = mrpt::math::CVectorFixedDouble<1>;
    const double phi0 = model.predict(landmark, robot)[0];
    Vec3 x0;
    for (int i = 0; i < 3; i++)
        x0[i] = wrt_pose ? (i == 0 ? robot.x : i == 1 ? robot.y : robot.phi) : landmark[i];
    const std::function<void(const Vec3&, const int&, Vec1&)> f = [&](const Vec3& x, const int&,
                                                                      Vec1& out) {
        const TPose2D r = wrt_pose ? TPose2D(x[0], x[1], x[2]) : robot;
        const Vector3d m = wrt_pose ? landmark : Vector3d(x[0], x[1], x[2]);
        out[0] = wrap(model.predict(m, r)[0] - phi0);
    };
    Vec3 step;
    step.fill(1e-6);
    mrpt::math::CMatrixDouble J;
    mrpt::math::estimateJacobian(x0, f, step, 0, J);
    return J.asEigen().row(0);
}

}  // namespace

TEST(PlanarBearingModel, PredictsTheAzimuthOfTheLandmark)
{
    const auto model = planarModel();
    // h = atan2(l_y − y, l_x − x) − θ: a landmark 1 m left and 1 m ahead of a robot facing +y
    const TPose2D robot(1, 2, M_PI / 2);
    auto z = model.predict({0, 3, 5}, robot);  // the landmark's z is ignored
    EXPECT_NEAR(z[0], M_PI / 4, 1e-12);
    EXPECT_DOUBLE_EQ(z[1], BearingMeasurementModel::kPlanarTheta);
    // wrapped: a landmark behind on the right
    z = model.predict({1.5, 1, 0}, robot);
    EXPECT_NEAR(z[0], wrap(std::atan2(-1, 0.5) - M_PI / 2), 1e-12);
    EXPECT_LT(z[0], -M_PI / 2);
    // a sensor 0.2 m ahead of the robot and turned 90° left
    const auto offset = planarModel(0.2, 0, M_PI / 2);
    z = offset.predict({1, 3, 0}, TPose2D(0, 0, 0));
    EXPECT_NEAR(z[0], wrap(std::atan2(3, 0.8) - M_PI / 2), 1e-12);
    // pitch and roll of the mounting do not tilt the planar sensor
    const BearingMeasurementModel tilted(mrpt::poses::CPose3D(0, 0, 1, 0, 20 * kDeg, 10 * kDeg),
                                         TMeasurementModelKind::Planar);
    EXPECT_NEAR(tilted.predict({2, 2, 0}, TPose2D(0, 0, 0))[0], M_PI / 4, 1e-12);
}

TEST(PlanarBearingModel, JacobiansMatchNumericDerivatives)
{
    mrpt::random::CRandomGenerator rng(42);
    for (int k = 0; k < 200; k++) {
        const auto model = planarModel(rng.drawUniform(-0.3, 0.3), rng.drawUniform(-0.3, 0.3),
                                       rng.drawUniform(-M_PI, M_PI));
        const TPose2D robot(rng.drawUniform(0, 15), rng.drawUniform(0, 8),
                            rng.drawUniform(-M_PI, M_PI));
        Vector3d landmark(rng.drawUniform(0, 15), rng.drawUniform(0, 8), 0);
        if ((landmark.head<2>() - Vector2d(robot.x, robot.y)).norm() < 0.5) continue;
        const auto pred = model.predictWithJacobians(landmark, robot);
        ASSERT_TRUE(pred.valid);
        EXPECT_NEAR(pred.z[0], model.predict(landmark, robot)[0], 1e-15);
        const Eigen::RowVector3d Hx = numericAzimuthJacobian(model, robot, landmark, true);
        const Eigen::RowVector3d Hm = numericAzimuthJacobian(model, robot, landmark, false);
        EXPECT_LT((pred.H_x.row(0) - Hx).cwiseAbs().maxCoeff(), 1e-6)
            << "case " << k << ": H_x " << pred.H_x.row(0) << " numeric " << Hx;
        EXPECT_LT((pred.H_m.row(0) - Hm).cwiseAbs().maxCoeff(), 1e-6)
            << "case " << k << ": H_m " << pred.H_m.row(0) << " numeric " << Hm;
        // θ carries nothing: its rows are zero, and so is ∂φ/∂m_z
        EXPECT_EQ(pred.H_x.row(1).cwiseAbs().maxCoeff(), 0.0);
        EXPECT_EQ(pred.H_m.row(1).cwiseAbs().maxCoeff(), 0.0);
        EXPECT_EQ(pred.H_m(0, 2), 0.0);
    }
    // Without a sensor offset the Jacobians are the textbook ones of atan2(l − p) − θ
    const auto model = planarModel();
    const auto pred = model.predictWithJacobians({4, 3, 0}, TPose2D(1, -1, 0.3));
    const double dx = 3, dy = 4, r2 = 25;
    EXPECT_NEAR(pred.H_x(0, 0), dy / r2, 1e-15);
    EXPECT_NEAR(pred.H_x(0, 1), -dx / r2, 1e-15);
    EXPECT_NEAR(pred.H_x(0, 2), -1, 1e-15);
    EXPECT_NEAR(pred.H_m(0, 0), -dy / r2, 1e-15);
    EXPECT_NEAR(pred.H_m(0, 1), dx / r2, 1e-15);
}

TEST(PlanarBearingModel, LandmarkAtTheSensorIsUndefined)
{
    const auto model = planarModel(0.2, 0, 0);
    EXPECT_FALSE(model.predictWithJacobians({1.2, 2, 0}, TPose2D(1, 2, 0)).valid);
    EXPECT_TRUE(model.predictWithJacobians({1.21, 2, 0}, TPose2D(1, 2, 0)).valid);
}

TEST(PlanarBearingModel, RaysAreHorizontalBearingLines)
{
    const auto model = planarModel(0.2, 0.1, 0.5);
    const TPose2D robot(3, 1, -0.4);
    const Vector3d landmark(6, 4, 0);
    const Vector3d o = model.rayOriginInMap(robot);
    const Vector3d d = model.rayDirectionInMap(model.predict(landmark, robot), robot);
    EXPECT_DOUBLE_EQ(o.z(), 0.0);
    EXPECT_DOUBLE_EQ(d.z(), 0.0);
    EXPECT_NEAR(d.norm(), 1, 1e-15);
    // the ray of the predicted azimuth passes through the landmark
    const Vector3d to = landmark - o;
    EXPECT_NEAR(d.x() * to.y() - d.y() * to.x(), 0, 1e-12);
    EXPECT_GT(d.dot(to), 0);
}

namespace {
struct TRay {
    Vector3d origin, dir;
};
/// The bearing line seen from robot of a point, or of an explicit azimuth
TRay rayTo(const BearingMeasurementModel& m, const TPose2D& robot, const Vector3d& point)
{
    return {m.rayOriginInMap(robot), m.rayDirectionInMap(m.predict(point, robot), robot)};
}
TRay rayAt(const BearingMeasurementModel& m, const TPose2D& robot, double azimuth)
{
    return {m.rayOriginInMap(robot),
            m.rayDirectionInMap({azimuth, BearingMeasurementModel::kPlanarTheta}, robot)};
}
mrpt_vslam::omni_fastslam::TRayCrossPoint cross(const TRay& a, const TRay& b)
{
    return mrpt_vslam::omni_fastslam::computeRayCrossPoint(a.origin, a.dir, b.origin, b.dir);
}
/// Closed form of two lines o_i + s_i (cos α_i, sin α_i) by Cramer's rule: (s_1, s_2)
Vector2d cramer(const Vector2d& o1, double a1, const Vector2d& o2, double a2)
{
    // s1 d1 − s2 d2 = o2 − o1
    const double det = std::cos(a1) * -std::sin(a2) + std::sin(a1) * std::cos(a2);
    const Vector2d b = o2 - o1;
    return {(b.x() * -std::sin(a2) + std::cos(a2) * b.y()) / det,
            (std::cos(a1) * b.y() - std::sin(a1) * b.x()) / det};
}
}  // namespace

TEST(PlanarCrossPoint, ExactCrossingMatchesClosedForm)
{
    const auto model = planarModel();
    const TPose2D r1(0, 0, 0.2), r2(1.5, -0.5, 0.9);
    const double phi1 = 0.6, phi2 = 0.9;  // azimuths in the robot frames
    const auto x = cross(rayAt(model, r1, phi1), rayAt(model, r2, phi2));
    ASSERT_FALSE(x.parallel);
    const Vector2d s = cramer({0, 0}, 0.2 + phi1, {1.5, -0.5}, 0.9 + phi2);
    EXPECT_NEAR(x.s1, s[0], 1e-12);
    EXPECT_NEAR(x.s2, s[1], 1e-12);
    EXPECT_NEAR(x.point.x(), s[0] * std::cos(0.2 + phi1), 1e-12);
    EXPECT_NEAR(x.point.y(), s[0] * std::sin(0.2 + phi1), 1e-12);
    EXPECT_NEAR(x.point.z(), 0, 1e-15);
    EXPECT_NEAR(x.gap, 0, 1e-12);
    EXPECT_NEAR(x.angle, std::abs((0.9 + phi2) - (0.2 + phi1)), 1e-12);

    // a landmark seen from two poses is recovered, and passes the tests
    const Vector3d landmark(4, 3, 0);
    const TPose2D a(0, 0, 0.3), b(1, -1, 1.2);
    const auto y = cross(rayTo(model, a, landmark), rayTo(model, b, landmark));
    EXPECT_LT((y.point - landmark).norm(), 1e-12);
    EXPECT_NEAR(y.s1, 5, 1e-12);
    EXPECT_NEAR(y.s2, std::hypot(3, 4), 1e-12);
    const TCrossPointLimits limits = limitsOf(5 * kDeg, 6.0, true);
    EXPECT_TRUE(mrpt_vslam::omni_fastslam::crossPointHasParallax(y.angle, limits));
    EXPECT_TRUE(mrpt_vslam::omni_fastslam::crossPointInFront(y, model.rayOriginInMap(a),
                                                             model.rayOriginInMap(b), limits));
}

TEST(PlanarCrossPoint, ParallelRaysAreFlagged)
{
    const auto model = planarModel();
    // same azimuth in the map from two positions side by side, and the opposite direction
    const auto x = cross(rayAt(model, TPose2D(0, 0, 0), 0.4), rayAt(model, TPose2D(0, 1, 0), 0.4));
    EXPECT_TRUE(x.parallel);
    const auto y =
        cross(rayAt(model, TPose2D(0, 0, 0), 0.4), rayAt(model, TPose2D(0, 1, M_PI), 0.4));
    EXPECT_TRUE(y.parallel);
}

TEST(PlanarCrossPoint, CrossingBehindARayIsRejected)
{
    const auto model = planarModel();
    const TCrossPointLimits limits = limitsOf(5 * kDeg, 0, true);
    // ray 1 along +x from the origin; ray 2 from (−2, 2) heading down-left: they cross at
    // x < 0, behind ray 1 (and in front of ray 2)
    const TPose2D r1(0, 0, 0), r2(-2, 2, 0);
    const auto x = cross(rayAt(model, r1, 0), rayAt(model, r2, -3 * M_PI / 4));
    ASSERT_FALSE(x.parallel);
    const Vector2d s = cramer({0, 0}, 0, {-2, 2}, -3 * M_PI / 4);
    EXPECT_NEAR(x.s1, s[0], 1e-12);
    EXPECT_NEAR(x.s1, -4, 1e-12);
    EXPECT_GT(x.s2, 0);
    EXPECT_FALSE(mrpt_vslam::omni_fastslam::crossPointInFront(x, model.rayOriginInMap(r1),
                                                              model.rayOriginInMap(r2), limits));
    // the same pair with ray 2 reversed crosses in front of ray 1 but behind ray 2
    const auto y = cross(rayAt(model, r1, 0), rayAt(model, r2, M_PI / 4));
    EXPECT_LT(y.s1, 0);
    EXPECT_LT(y.s2, 0);
    EXPECT_FALSE(mrpt_vslam::omni_fastslam::crossPointInFront(y, model.rayOriginInMap(r1),
                                                              model.rayOriginInMap(r2), limits));
}

TEST(PlanarCrossPoint, LowParallaxAndFarCrossingsAreRejected)
{
    const auto model = planarModel();
    const TCrossPointLimits limits = limitsOf(5 * kDeg, 6.0, true);
    const Vector3d landmark(5, 0, 0);
    // 0.3 m of baseline across the line of sight at 5 m: parallax atan(0.3/5) = 3.4° < 5°
    const auto low =
        cross(rayTo(model, TPose2D(0, 0, 0), landmark), rayTo(model, TPose2D(0, 0.3, 0), landmark));
    ASSERT_FALSE(low.parallel);
    EXPECT_NEAR(low.angle, std::atan2(0.3, 5), 1e-12);
    EXPECT_LT((low.point - landmark).norm(), 1e-9);
    EXPECT_FALSE(mrpt_vslam::omni_fastslam::crossPointHasParallax(low.angle, limits));
    // 0.6 m: 6.8° passes
    const auto ok =
        cross(rayTo(model, TPose2D(0, 0, 0), landmark), rayTo(model, TPose2D(0, 0.6, 0), landmark));
    EXPECT_TRUE(mrpt_vslam::omni_fastslam::crossPointHasParallax(ok.angle, limits));
    // two rays meeting nearly head-on (the landmark between the robots): the directions are
    // 177.1° apart, the lines only 2.9°; the spherical test (directions) would accept it
    const Vector3d between(2, 0.1, 0);
    const auto head_on =
        cross(rayTo(model, TPose2D(0, 0, 0), between), rayTo(model, TPose2D(4, 0.1, 0), between));
    EXPECT_GT(head_on.angle, M_PI - 5 * kDeg);
    EXPECT_FALSE(mrpt_vslam::omni_fastslam::crossPointHasParallax(head_on.angle, limits));
    EXPECT_TRUE(mrpt_vslam::omni_fastslam::crossPointHasParallax(head_on.angle,
                                                                 limitsOf(5 * kDeg, 6.0, false)));
    // a good parallax but 8 m away from the first robot: beyond max_range = 6 m
    const Vector3d far(8, 0, 0);
    const TPose2D a(0, 0, 0), b(5, -3, 0);
    const auto x = cross(rayTo(model, a, far), rayTo(model, b, far));
    EXPECT_TRUE(mrpt_vslam::omni_fastslam::crossPointHasParallax(x.angle, limits));
    EXPECT_NEAR(x.s1, 8, 1e-12);
    EXPECT_NEAR(x.s2, std::hypot(3, 3), 1e-12);
    EXPECT_FALSE(mrpt_vslam::omni_fastslam::crossPointInFront(x, model.rayOriginInMap(a),
                                                              model.rayOriginInMap(b), limits));
    EXPECT_TRUE(mrpt_vslam::omni_fastslam::crossPointInFront(
        x, model.rayOriginInMap(a), model.rayOriginInMap(b), limitsOf(5 * kDeg, 0, true)));
    // and a crossing nearer than min_range = 4.5 m to the second robot (4.24 m) is not valid
    EXPECT_FALSE(mrpt_vslam::omni_fastslam::crossPointInFront(
        x, model.rayOriginInMap(a), model.rayOriginInMap(b), limitsOf(5 * kDeg, 0, true, 4.5)));
    EXPECT_TRUE(mrpt_vslam::omni_fastslam::crossPointInFront(
        x, model.rayOriginInMap(a), model.rayOriginInMap(b), limitsOf(5 * kDeg, 0, true, 4.0)));
}
