#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt_vslam/omni_fastslam/LightMapElements.h>

#include <Eigen/Core>

namespace mrpt_vslam::omni_fastslam {

/** Bearing-only measurement model of an upward fisheye camera looking at ceiling lights
 *  (Gamallo, Mucientes & Regueiro, "A FastSLAM-based Algorithm for Omnidirectional Cameras",
 *  2013, Sec. III-A; doc/omni-fastslam.md Eq. M1-M4).
 *
 *  Conventions:
 *  - the robot pose is planar, x = (x, y, yaw), on the floor (z = 0);
 *  - the camera sits at `sensor_in_robot` (default (0, 0, 1.8) m, axes aligned with the robot's);
 *  - a measurement is z = (φ, θ): φ is the azimuth around the camera's z (optical) axis measured
 *    from its x axis, θ the angle from the optical axis (the θ of Eq. 1);
 *  - landmarks m are 3D points in the map frame.
 *
 *  Steps of h(m, x):
 *  1. camera pose in the map: C = (x, y, 0, yaw, 0, 0) ⊕ sensor_in_robot           (Eq. M1)
 *  2. landmark in the camera frame: d = R_C^T (m − t_C)                            (Eq. M2)
 *  3. angles: φ = atan2(d_y, d_x), θ = atan2(√(d_x² + d_y²), d_z)                  (Eq. M3)
 *  4. Jacobians by the chain rule: H = ∂(φ, θ)/∂d · ∂d/∂(x | m)                      (Eq. M4)
 *
 *  Planar model (`TMeasurementModelKind::Planar`, doc/omni-fastslam.md §12, Eq. P1-P3): the
 *  sensor measures the azimuth only, landmarks are points of the robot's plane (z = 0). Only
 *  (x, y, yaw) of `sensor_in_robot` count. z = (φ, π/2): θ is the constant of a horizontal
 *  direction, its rows of H_x and H_m are zero, so its innovation is always 0 and it carries no
 *  information; the map evaluates likelihoods on φ alone.
 *  1. sensor position and heading: t_c = (x, y) + R(yaw) t_s, ψ = yaw + yaw_s        (Eq. P1)
 *  2. φ = atan2(m_y − t_cy, m_x − t_cx) − ψ, wrapped                                 (Eq. P2)
 *  3. ∂φ/∂m = (−Δ_y, Δ_x, 0)/|Δ|², ∂φ/∂(x, y) = −∂φ/∂m_{xy},
 *     ∂φ/∂yaw = −∂φ/∂m_{xy} · R'(yaw) t_s − 1, Δ = m − t_c                            (Eq. P3)
 */
class BearingMeasurementModel {
  public:
    using Vector2 = Eigen::Vector2d;
    using Vector3 = Eigen::Vector3d;
    using Matrix23 = Eigen::Matrix<double, 2, 3>;

    /// Prediction of one measurement and its Jacobians.
    struct TPrediction {
        Vector2 z = Vector2::Zero();                ///< predicted (φ, θ) [rad]
        Matrix23 H_x = Matrix23::Zero();            ///< ∂h/∂(x, y, yaw) [rad/m, rad/m, rad/rad]
        Matrix23 H_m = Matrix23::Zero();            ///< ∂h/∂(m_x, m_y, m_z) [rad/m]
        Vector3 point_in_camera = Vector3::Zero();  ///< d of Eq. M2 [m]
        /// false when the landmark is (numerically) on the optical axis or at the camera centre,
        /// where φ and the Jacobians are undefined.
        bool valid = false;
    };

    BearingMeasurementModel() = default;
    /** \param sensor_in_robot camera pose on the robot (z up, optical axis = camera +z)
     *  \param kind spherical (φ, θ) or planar (azimuth only) */
    explicit BearingMeasurementModel(const mrpt::poses::CPose3D& sensor_in_robot,
                                     TMeasurementModelKind kind = TMeasurementModelKind::Spherical);

    TMeasurementModelKind kind() const { return m_kind; }
    bool isPlanar() const { return m_kind == TMeasurementModelKind::Planar; }
    /// θ of every planar measurement and prediction: a horizontal direction [rad].
    static constexpr double kPlanarTheta = M_PI / 2;

    const mrpt::poses::CPose3D& sensorInRobot() const { return m_sensor_in_robot; }
    void setSensorInRobot(const mrpt::poses::CPose3D& sensor_in_robot);

    /// Camera pose in the map for a planar robot pose (Eq. M1; planar: Eq. P1, on the floor).
    mrpt::poses::CPose3D cameraInMap(const mrpt::math::TPose2D& robot_in_map) const;

    /// h(m, x) only (Eq. M1-M3). Undefined φ (landmark on the optical axis) gives φ = 0.
    Vector2 predict(const Vector3& landmark_in_map, const mrpt::math::TPose2D& robot_in_map) const;

    /// h(m, x) with its analytic Jacobians H_x and H_m (Eq. M4).
    TPrediction predictWithJacobians(const Vector3& landmark_in_map,
                                     const mrpt::math::TPose2D& robot_in_map) const;

    /** The model at one robot pose, for predicting many landmarks from it: what depends on the
     *  pose alone (R_z(yaw); planar: t_c and ψ) is computed once. Its predictions equal
     *  predict() and predictWithJacobians() at that pose bit for bit. */
    class AtPose {
      public:
        AtPose(const BearingMeasurementModel& model, const mrpt::math::TPose2D& robot_in_map);
        Vector2 predict(const Vector3& landmark_in_map) const;
        TPrediction predictWithJacobians(const Vector3& landmark_in_map) const;
        const mrpt::math::TPose2D& robot() const { return m_robot; }

      private:
        TPrediction predictPlanar(const Vector3& landmark_in_map) const;

        bool m_planar;
        mrpt::math::TPose2D m_robot;
        Eigen::Matrix3d m_Rz, m_RsT;  ///< spherical: R_z(yaw) and the sensor's R_sᵀ
        Vector3 m_t_s;                ///< spherical: the sensor's position on the robot
        double m_c = 1, m_s = 0, m_tx = 0, m_ty = 0, m_psi = 0;  ///< planar: Eq. P1's terms
        Eigen::Vector2d m_t_c = Eigen::Vector2d::Zero();         ///< planar: Eq. P1
    };
    AtPose atPose(const mrpt::math::TPose2D& robot_in_map) const
    {
        return AtPose(*this, robot_in_map);
    }

    /// Camera centre in the map frame [m]: the origin of every measurement ray.
    Vector3 rayOriginInMap(const mrpt::math::TPose2D& robot_in_map) const;
    /// Unit direction, in the map frame, of the ray of measurement z taken from robot_in_map.
    Vector3 rayDirectionInMap(const Vector2& z, const mrpt::math::TPose2D& robot_in_map) const;

    /// Unit direction in the camera frame of the angles z = (φ, θ).
    static Vector3 directionOfAngles(const Vector2& z);
    /// Angles (φ, θ) of a direction (any length) in the camera frame (Eq. M3).
    static Vector2 anglesOfDirection(const Vector3& direction_in_camera);

    /// Innovation z − ẑ with the azimuth difference wrapped to (−π, π].
    static Vector2 innovation(const Vector2& z, const Vector2& z_predicted);

    /** (φ, θ) of an `OMNICAM_BEARINGS` `CObservationBearingRange` entry: φ = yaw,
     *  θ = π/2 + pitch (pitch = −elevation). The Jacobian of this change is the identity. */
    static Vector2 anglesOfYawPitch(double yaw, double pitch);

  private:
    /// The sensor pose as the model uses it (planar: its x, y and yaw only).
    static mrpt::poses::CPose3D sensorPoseFor(const mrpt::poses::CPose3D& sensor_in_robot,
                                              TMeasurementModelKind kind);

    mrpt::poses::CPose3D m_sensor_in_robot{0, 0, 1.8, 0, 0, 0};
    TMeasurementModelKind m_kind = TMeasurementModelKind::Spherical;
};

}  // namespace mrpt_vslam::omni_fastslam
