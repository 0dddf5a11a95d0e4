#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationVisualLandmarks.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/USurfDescriptor.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace mrpt_vslam::multirobot {

/** One stereo observation o_t = (z_t, d_t) of Gil et al. 2010 (Sec. 3), moved from the camera
 *  frame into the robot frame, which does not depend on the particle: the point and R_t rotated by
 *  the camera's pose on the robot. */
struct TLandmarkMeasurement {
    Eigen::Vector3d z = Eigen::Vector3d::Zero();  ///< point in the robot frame [m]
    Eigen::Matrix3d R = Eigen::Matrix3d::Zero();  ///< its covariance R_t in the robot frame [m²]
    core::USurfDescriptor::TDescriptor d{};       ///< U-SURF descriptor d_t
    double depth = 0;  ///< distance along the optical axis or range [m]: B-selection key
    /// Front-end track, or the landmark's identity in range-bearing data that keeps it (−1:
    /// hidden). Diagnostics (association errors).
    int64_t track_id = -1;
    /// The landmark's identity where the data gives one (range-bearing `landmarkID` ≥ 0), else
    /// −1: associates only with `associate_by_identity` (known correspondences).
    int64_t identity = -1;
    /// Which of the robot's observations of the step it came from (0, 1, ...: one per sensor).
    /// A frame's measurements are associated one-to-one per sensor, sensor after sensor, so
    /// that one sensor's may take the landmarks another started in the same frame.
    uint16_t sensor = 0;
    /// A range-bearing reading of the planar model: its height is the sensor plane's, not read.
    bool planar = false;
};

/** The same measurement in the map frame for one particle's robot pose x:
 *  z_w = g⁻¹(x, z) = R(θ) z + (x, y, 0), R_w = R(θ) R R(θ)^T. */
struct TMapMeasurement {
    Eigen::Vector3d z;
    Eigen::Matrix3d R;
};

/** The measurements of a `CObservationVisualLandmarks` (one per CLandmark: pose_mean in the
 *  camera frame, pose_cov_* = R_t, U-SURF in features[0].descriptors.SURF), in the robot frame.
 *  \throw std::runtime_error naming the label if a landmark has no 64-D SURF descriptor or a
 *  non-finite point or covariance. */
std::vector<TLandmarkMeasurement> measurementsFromObservation(
    const mrpt::obs::CObservationVisualLandmarks& obs);

/** Noise of range-bearing measurements (`CObservationBearingRange`). Each σ that is not set
 *  here is the observation's own (`sensor_std_range`, `sensor_std_yaw`, `sensor_std_pitch`).
 *  A pitch σ > 0 makes the model spatial (3D landmarks); with σ_pitch = 0 it is planar: the
 *  pitch must be 0 and the landmark's height is measured as 0 with σ_height. */
struct TRangeBearingNoise {
    std::optional<double> std_range;    ///< [m]
    std::optional<double> std_bearing;  ///< [rad]
    double std_height = 0.01;           ///< [m], planar model only
    std::optional<double> std_pitch;    ///< [rad]
    /// For messages: `SECTION.PREFIX` of the ini keys that set these σ (PREFIX_std_range, ...),
    /// as `--set` takes them; empty when they do not come from an ini file.
    std::string config_keys;
};

/** The measurements of a `CObservationBearingRange` in the robot frame: the point
 *  r (cos p cos b, cos p sin b, −sin p) in the sensor frame (MRPT's convention: pitch p positive
 *  downwards), its covariance J S Jᵀ (J = ∂point/∂(r, b, p)), S = diag(σ_r², σ_b², σ_p²) of
 *  sensor_std_* or, with `validCovariances`, the measurement's own covariance of (r, b, p) (a σ
 *  the options set replaces the observation's in either), or in the planar model (no pitch
 *  noise) the
 *  same without the pitch terms and with σ_h² in height, both moved by the sensor's pose on
 *  the robot (`sensorLocationOnRobot`); no descriptor (all zeros: association by the gate
 *  alone); track_id = landmarkID. A reading with a range ≤ 0 (noise on a very near landmark)
 *  is left out and counted in `non_positive` when given.
 *  \throw std::runtime_error naming the label for a missing or non-finite σ, a non-finite
 *  range, bearing or pitch, or a non-zero pitch in the planar model. */
std::vector<TLandmarkMeasurement> measurementsFromBearingRange(
    const mrpt::obs::CObservationBearingRange& obs, const TRangeBearingNoise& noise,
    size_t* non_positive = nullptr);

/** `z` cut into one list per sensor (TLandmarkMeasurement::sensor), in increasing sensor
 *  index, each in the order of `z`; none for an empty `z`. */
std::vector<std::vector<TLandmarkMeasurement>> splitBySensor(
    const std::vector<TLandmarkMeasurement>& z);

/** The (at most) B measurements with the smallest depth, the most precise for a stereo pair,
 *  in that order (ties: in the order given); all of them if B = 0 or fewer. */
std::vector<TLandmarkMeasurement> selectNearest(std::vector<TLandmarkMeasurement> z, size_t B);

/** B measurements drawn uniformly without replacement (all of them if B = 0 or fewer), ordered
 *  by depth as selectNearest() orders them, so that only which ones are kept differs. */
std::vector<TLandmarkMeasurement> selectAtRandom(std::vector<TLandmarkMeasurement> z, size_t B,
                                                 mrpt::random::CRandomGenerator& rng);

/** The map-frame transform of a robot pose, x = (x, y, θ): translation and cos θ, sin θ once,
 *  for the many measurements fused from it. */
struct TPlanarTransform {
    double x, y, c, s;
    explicit TPlanarTransform(const mrpt::math::TPose2D& robot)
        : x(robot.x), y(robot.y), c(std::cos(robot.phi)), s(std::sin(robot.phi))
    {
    }
};

/// The measurement in the map frame seen from a robot pose (R(θ) turns about z only, so the
/// products are written out).
inline TMapMeasurement toMapFrame(const TLandmarkMeasurement& m, const TPlanarTransform& t)
{
    const double c = t.c, s = t.s;
    const Eigen::Matrix3d& R = m.R;
    TMapMeasurement w;
    w.z = {c * m.z.x() - s * m.z.y() + t.x, s * m.z.x() + c * m.z.y() + t.y, m.z.z()};
    const double a = R(0, 0), b = R(0, 1), e = R(1, 1), d = R(0, 2), f = R(1, 2);
    const double xx = c * c * a - 2 * c * s * b + s * s * e;
    const double xy = c * s * (a - e) + (c * c - s * s) * b;
    const double yy = s * s * a + 2 * c * s * b + c * c * e;
    const double xz = c * d - s * f, yz = s * d + c * f;
    w.R << xx, xy, xz, xy, yy, yz, xz, yz, R(2, 2);
    return w;
}

inline TMapMeasurement toMapFrame(const TLandmarkMeasurement& m, const mrpt::math::TPose2D& robot)
{
    return toMapFrame(m, TPlanarTransform(robot));
}

/// H = ∂z_w/∂(x, y, θ) of a point z_w measured from `robot`: identity in x, y, and ∂R(θ)z/∂θ.
inline Eigen::Matrix3d poseJacobian(const Eigen::Vector3d& z_w, const mrpt::math::TPose2D& robot)
{
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    H(0, 0) = H(1, 1) = 1;
    H(0, 2) = -(z_w.y() - robot.y);
    H(1, 2) = z_w.x() - robot.x;
    return H;
}

}  // namespace mrpt_vslam::multirobot
