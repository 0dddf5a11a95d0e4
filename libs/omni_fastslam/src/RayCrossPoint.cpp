#include <mrpt_vslam/omni_fastslam/RayCrossPoint.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace mrpt_vslam::omni_fastslam {

double angleBetweenDirections(const Eigen::Vector3d& dir1, const Eigen::Vector3d& dir2)
{
    // atan2 keeps full precision for nearly (anti)parallel directions, unlike acos
    return std::atan2(dir1.cross(dir2).norm(), dir1.dot(dir2));
}

TRayCrossPoint computeRayCrossPoint(const Eigen::Vector3d& origin1, const Eigen::Vector3d& dir1,
                                    const Eigen::Vector3d& origin2, const Eigen::Vector3d& dir2,
                                    double parallel_sin_tol)
{
    TRayCrossPoint out;
    out.angle = angleBetweenDirections(dir1, dir2);
    const double a = dir1.squaredNorm(), b = dir1.dot(dir2), c = dir2.squaredNorm();
    // a c − b² = |d1|² |d2|² sin²(angle)
    const double denom = a * c - b * b;
    if (!(a > 0 && c > 0) || denom <= parallel_sin_tol * parallel_sin_tol * a * c) {
        out.parallel = true;
        return out;
    }
    const Eigen::Vector3d w0 = origin1 - origin2;
    const double d = dir1.dot(w0), e = dir2.dot(w0);
    // Eq. X1: minimise |o1 + s1 d1 − o2 − s2 d2|²  →  s1 = (b e − c d)/(a c − b²),
    //                                                 s2 = (a e − b d)/(a c − b²)
    out.s1 = (b * e - c * d) / denom;
    out.s2 = (a * e - b * d) / denom;
    const Eigen::Vector3d p1 = origin1 + out.s1 * dir1;
    const Eigen::Vector3d p2 = origin2 + out.s2 * dir2;
    // Eq. X2: cross-point = midpoint of the common perpendicular
    out.point = 0.5 * (p1 + p2);
    out.gap = (p1 - p2).norm();
    return out;
}

bool crossPointHasParallax(double angle, const TCrossPointLimits& limits)
{
    // planar: the angle between the two lines, not between the two directions
    const double parallax = limits.planar ? std::min(angle, M_PI - angle) : angle;
    return parallax > limits.min_angle;
}

bool crossPointInFront(const TRayCrossPoint& x, const Eigen::Vector3d& origin1,
                       const Eigen::Vector3d& origin2, const TCrossPointLimits& limits)
{
    if (x.parallel || !(x.s1 > limits.min_range && x.s2 > limits.min_range) ||
        !(x.s1 > 0 && x.s2 > 0))
        return false;
    if (!limits.planar && !(x.point.z() > std::max(origin1.z(), origin2.z()))) return false;
    // unit directions: s_i is the distance from origin i along its ray
    return limits.max_range <= 0 || (x.s1 <= limits.max_range && x.s2 <= limits.max_range);
}

}  // namespace mrpt_vslam::omni_fastslam
