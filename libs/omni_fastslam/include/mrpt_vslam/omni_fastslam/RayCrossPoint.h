#pragma once

#include <Eigen/Core>

namespace mrpt_vslam::omni_fastslam {

/** The "cross-point" of two measurement rays (paper 000, Sec. III-F, Fig. 3): the 3D point
 *  closest to both rays, i.e. the midpoint of their common perpendicular
 *  (doc/omni-fastslam.md Eq. X1-X2).
 *
 *  Ray i is o_i + s_i d_i. The parameters s_i are in the units of d_i (metres for unit
 *  directions); s_i ≤ 0 means the cross-point lies behind camera i.
 */
struct TRayCrossPoint {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< midpoint of the common perpendicular [m]
    double gap = 0;       ///< length of the common perpendicular (0 for intersecting rays) [m]
    double s1 = 0;        ///< parameter of the closest point on ray 1
    double s2 = 0;        ///< parameter of the closest point on ray 2
    double angle = 0;     ///< angle between the two directions, in [0, π] [rad]
    bool parallel = false;  ///< directions (anti)parallel within tolerance: nothing else is set
};

/** Closest point to two rays (Eq. X1-X2).
 *  \param parallel_sin_tol rays with |sin(angle)| below this are flagged `parallel` */
TRayCrossPoint computeRayCrossPoint(const Eigen::Vector3d& origin1, const Eigen::Vector3d& dir1,
                                    const Eigen::Vector3d& origin2, const Eigen::Vector3d& dir2,
                                    double parallel_sin_tol = 1e-9);

/// Angle between two directions (any length), in [0, π] [rad]; the ANG of the ANG_min test.
double angleBetweenDirections(const Eigen::Vector3d& dir1, const Eigen::Vector3d& dir2);

}  // namespace mrpt_vslam::omni_fastslam
