#include <mrpt_vslam/omni_fastslam/BearingMeasurementModel.h>

#include <cmath>

namespace mrpt_vslam::omni_fastslam {

namespace {
/// Squared distance to the optical axis below which φ is considered undefined [m²].
constexpr double kMinAxisDistance2 = 1e-18;

Eigen::Matrix3d rotationZ(double yaw)
{
    const double c = std::cos(yaw), s = std::sin(yaw);
    Eigen::Matrix3d R;
    R << c, -s, 0, s, c, 0, 0, 0, 1;
    return R;
}

/// Angle wrapped to (−π, π].
double wrapAngle(double a)
{
    if (a > -M_PI && a <= M_PI) return a;  // what remainder() returns there, without its cost
    a = std::remainder(a, 2 * M_PI);
    return a <= -M_PI ? a + 2 * M_PI : a;
}
}  // namespace

BearingMeasurementModel::BearingMeasurementModel(const mrpt::poses::CPose3D& sensor_in_robot,
                                                 TMeasurementModelKind kind)
    : m_sensor_in_robot(sensorPoseFor(sensor_in_robot, kind)), m_kind(kind)
{
}

mrpt::poses::CPose3D BearingMeasurementModel::sensorPoseFor(
    const mrpt::poses::CPose3D& sensor_in_robot, TMeasurementModelKind kind)
{
    // Planar: only the sensor's (x, y, yaw) on the robot count; it looks horizontally.
    return kind == TMeasurementModelKind::Planar
               ? mrpt::poses::CPose3D(sensor_in_robot.x(), sensor_in_robot.y(), 0,
                                      sensor_in_robot.yaw(), 0, 0)
               : sensor_in_robot;
}

void BearingMeasurementModel::setSensorInRobot(const mrpt::poses::CPose3D& sensor_in_robot)
{
    m_sensor_in_robot = sensorPoseFor(sensor_in_robot, m_kind);
}

mrpt::poses::CPose3D BearingMeasurementModel::cameraInMap(
    const mrpt::math::TPose2D& robot_in_map) const
{
    // Eq. M1: C = (x, y, 0, yaw, 0, 0) ⊕ sensor_in_robot
    return mrpt::poses::CPose3D(robot_in_map.x, robot_in_map.y, 0, robot_in_map.phi, 0, 0) +
           m_sensor_in_robot;
}

BearingMeasurementModel::Vector2 BearingMeasurementModel::predict(
    const Vector3& landmark_in_map, const mrpt::math::TPose2D& robot_in_map) const
{
    return atPose(robot_in_map).predict(landmark_in_map);
}

BearingMeasurementModel::TPrediction BearingMeasurementModel::predictWithJacobians(
    const Vector3& landmark_in_map, const mrpt::math::TPose2D& robot_in_map) const
{
    return atPose(robot_in_map).predictWithJacobians(landmark_in_map);
}

BearingMeasurementModel::AtPose::AtPose(const BearingMeasurementModel& model,
                                        const mrpt::math::TPose2D& robot_in_map)
    : m_planar(model.isPlanar()), m_robot(robot_in_map)
{
    const auto& sensor = model.m_sensor_in_robot;
    if (m_planar) {
        m_c = std::cos(robot_in_map.phi);
        m_s = std::sin(robot_in_map.phi);
        m_tx = sensor.x();
        m_ty = sensor.y();
        // Eq. P1: t_c = (x, y) + R(yaw) t_s, ψ = yaw + yaw_s
        m_t_c = {robot_in_map.x + m_c * m_tx - m_s * m_ty,
                 robot_in_map.y + m_s * m_tx + m_c * m_ty};
        m_psi = robot_in_map.phi + sensor.yaw();
        return;
    }
    m_Rz = rotationZ(robot_in_map.phi);
    m_RsT = sensor.getRotationMatrix().asEigen().transpose();
    m_t_s = sensor.m_coords.asEigen();
}

BearingMeasurementModel::Vector2 BearingMeasurementModel::AtPose::predict(
    const Vector3& landmark_in_map) const
{
    if (m_planar) return predictPlanar(landmark_in_map).z;
    const Vector3 landmark_in_robot =
        m_Rz.transpose() * (landmark_in_map - Vector3(m_robot.x, m_robot.y, 0));
    // Eq. M2: d = R_s^T (R_z^T (m − p) − t_s)
    return anglesOfDirection(m_RsT * (landmark_in_robot - m_t_s));
}

BearingMeasurementModel::TPrediction BearingMeasurementModel::AtPose::predictWithJacobians(
    const Vector3& landmark_in_map) const
{
    if (m_planar) return predictPlanar(landmark_in_map);
    TPrediction out;
    // q: landmark in the robot frame; d: landmark in the camera frame (Eq. M2)
    const Vector3 q = m_Rz.transpose() * (landmark_in_map - Vector3(m_robot.x, m_robot.y, 0));
    const Vector3 d = m_RsT * (q - m_t_s);
    out.point_in_camera = d;
    out.z = anglesOfDirection(d);

    const double rho2 = d.x() * d.x() + d.y() * d.y();
    const double r2 = rho2 + d.z() * d.z();
    if (rho2 < kMinAxisDistance2 || r2 <= 0) return out;
    const double rho = std::sqrt(rho2);

    // Eq. M4: ∂φ/∂d = (−d_y, d_x, 0)/ρ²;  ∂θ/∂d = (d_x d_z / ρ, d_y d_z / ρ, −ρ) / r²
    Matrix23 dz_dd;
    dz_dd << -d.y() / rho2, d.x() / rho2, 0,  //
        d.x() * d.z() / (rho * r2), d.y() * d.z() / (rho * r2), -rho / r2;

    // ∂d/∂m = R_s^T R_z^T
    out.H_m = dz_dd * m_RsT * m_Rz.transpose();

    // ∂q/∂(x, y, yaw) = [−R_z^T e_x, −R_z^T e_y, (q_y, −q_x, 0)]
    Eigen::Matrix3d dq_dx;
    dq_dx.col(0) = -m_Rz.transpose().col(0);
    dq_dx.col(1) = -m_Rz.transpose().col(1);
    dq_dx.col(2) = Vector3(q.y(), -q.x(), 0);
    out.H_x = dz_dd * m_RsT * dq_dx;
    out.valid = true;
    return out;
}

BearingMeasurementModel::TPrediction BearingMeasurementModel::AtPose::predictPlanar(
    const Vector3& landmark_in_map) const
{
    TPrediction out;
    const double c = m_c, s = m_s, tx = m_tx, ty = m_ty, psi = m_psi;
    const Eigen::Vector2d delta = landmark_in_map.head<2>() - m_t_c;
    const double r2 = delta.squaredNorm();
    // the landmark in the sensor frame (horizontal)
    out.point_in_camera = Vector3(std::cos(psi) * delta.x() + std::sin(psi) * delta.y(),
                                  -std::sin(psi) * delta.x() + std::cos(psi) * delta.y(), 0);
    // Eq. P2: φ = atan2(Δ_y, Δ_x) − ψ
    out.z = {r2 < kMinAxisDistance2 ? 0.0 : wrapAngle(std::atan2(delta.y(), delta.x()) - psi),
             kPlanarTheta};
    if (r2 < kMinAxisDistance2) return out;

    // Eq. P3: ∂φ/∂m = (−Δ_y, Δ_x)/|Δ|²; t_c moves with (x, y) and turns with yaw
    const Eigen::Vector2d dphi_dm(-delta.y() / r2, delta.x() / r2);
    const Eigen::Vector2d dtc_dyaw(-s * tx - c * ty, c * tx - s * ty);
    out.H_m.row(0) << dphi_dm.x(), dphi_dm.y(), 0;
    out.H_x.row(0) << -dphi_dm.x(), -dphi_dm.y(), -dphi_dm.dot(dtc_dyaw) - 1;
    out.valid = true;
    return out;
}

BearingMeasurementModel::Vector3 BearingMeasurementModel::rayOriginInMap(
    const mrpt::math::TPose2D& robot_in_map) const
{
    return cameraInMap(robot_in_map).m_coords.asEigen();
}

BearingMeasurementModel::Vector3 BearingMeasurementModel::rayDirectionInMap(
    const Vector2& z, const mrpt::math::TPose2D& robot_in_map) const
{
    if (isPlanar()) {
        // the bearing line of azimuth φ in the plane: direction ψ + φ
        const double a = robot_in_map.phi + m_sensor_in_robot.yaw() + z[0];
        return {std::cos(a), std::sin(a), 0};
    }
    const Eigen::Matrix3d R_camera =
        rotationZ(robot_in_map.phi) * m_sensor_in_robot.getRotationMatrix().asEigen();
    return R_camera * directionOfAngles(z);
}

BearingMeasurementModel::Vector3 BearingMeasurementModel::directionOfAngles(const Vector2& z)
{
    const double st = std::sin(z[1]);
    return {st * std::cos(z[0]), st * std::sin(z[0]), std::cos(z[1])};
}

BearingMeasurementModel::Vector2 BearingMeasurementModel::anglesOfDirection(
    const Vector3& direction_in_camera)
{
    const Vector3& d = direction_in_camera;
    // Eq. M3 (metre-scale directions: no overflow for std::hypot to guard against)
    const double rho2 = d.x() * d.x() + d.y() * d.y();
    const double rho = std::sqrt(rho2);
    const double phi = rho2 < kMinAxisDistance2 ? 0.0 : std::atan2(d.y(), d.x());
    return {phi, std::atan2(rho, d.z())};
}

BearingMeasurementModel::Vector2 BearingMeasurementModel::innovation(const Vector2& z,
                                                                     const Vector2& z_predicted)
{
    return {wrapAngle(z[0] - z_predicted[0]), z[1] - z_predicted[1]};
}

BearingMeasurementModel::Vector2 BearingMeasurementModel::anglesOfYawPitch(double yaw, double pitch)
{
    return {wrapAngle(yaw), M_PI / 2 + pitch};
}

}  // namespace mrpt_vslam::omni_fastslam
