#pragma once

#include <Eigen/Core>

namespace mrpt_vslam::omni_fastslam {

/** The "cross-point" of two measurement rays (Gamallo et al. 2013, Sec. III-F, Fig. 3): the 3D
 *  point closest to both rays, i.e. the midpoint of their common perpendicular
 *  (doc/omni-fastslam.md Eq. X1-X2).
 *
 *  Ray i is o_i + s_i d_i. The parameters s_i are in the units of d_i (metres for unit
 *  directions); s_i ≤ 0 means the cross-point lies behind camera i.
 */
struct TRayCrossPoint {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< midpoint of the common perpendicular [m]
    double gap = 0;         ///< length of the common perpendicular (0 for intersecting rays) [m]
    double s1 = 0;          ///< parameter of the closest point on ray 1
    double s2 = 0;          ///< parameter of the closest point on ray 2
    double angle = 0;       ///< angle between the two directions, in [0, π] [rad]
    bool parallel = false;  ///< directions (anti)parallel within tolerance: nothing else is set
};

/** Closest point to two rays (Eq. X1-X2).
 *  \param parallel_sin_tol rays with |sin(angle)| below this are flagged `parallel` */
TRayCrossPoint computeRayCrossPoint(const Eigen::Vector3d& origin1, const Eigen::Vector3d& dir1,
                                    const Eigen::Vector3d& origin2, const Eigen::Vector3d& dir2,
                                    double parallel_sin_tol = 1e-9);

/// Angle between two directions (any length), in [0, π] [rad]; the ANG of the ANG_min test.
double angleBetweenDirections(const Eigen::Vector3d& dir1, const Eigen::Vector3d& dir2);

/** Geometric tests of a cross-point (Sec. III-F(1) tests a and b; doc/omni-fastslam.md §3, §12).
 *  Spherical (lights above the camera): angle > min_angle, in front of both cameras (s_i > 0)
 *  and above both. Planar (bearing lines in the robot's plane): parallax
 *  min(angle, π − angle) > min_angle — two lines meeting under an angle near π are as
 *  ill-conditioned as nearly parallel ones — and in front of both rays. Both: between min_range
 *  and max_range of both ray origins along the rays (max_range 0 = no limit). Directions must
 *  be unit vectors.
 */
struct TCrossPointLimits {
    double min_angle = 0;  ///< ANG_min [rad]
    double max_range = 0;  ///< [m], 0 = no limit
    bool planar = false;
    double min_range = 0;  ///< [m]
};
/** Test (a): the rays' angle (spherical) or the lines' parallax (planar) exceeds min_angle.
 *  \param angle the `angle` of a TRayCrossPoint that is not `parallel` [rad] */
bool crossPointHasParallax(double angle, const TCrossPointLimits& limits);
/// Test (b): in front of both rays (and above both origins, spherical), within the range limits.
bool crossPointInFront(const TRayCrossPoint& x, const Eigen::Vector3d& origin1,
                       const Eigen::Vector3d& origin2, const TCrossPointLimits& limits);

}  // namespace mrpt_vslam::omni_fastslam
