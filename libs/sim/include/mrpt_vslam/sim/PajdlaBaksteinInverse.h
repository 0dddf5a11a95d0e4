#pragma once

#include <mrpt_vslam/core/PajdlaBaksteinCamera.h>

#include <Eigen/Core>
#include <vector>

namespace mrpt_vslam::sim {

/** Inverse of the fisheye model of Gamallo et al. 2013, Eq. 1: pixel (u, v) → ray angles (φ, θ).
 *
 *  φ = atan2(v/β − v0, u − u0), r = |(u − u0, v/β − v0)|, and θ solves r(θ) = r: a table of
 *  r(θ) on [0, max_theta] gives the bracket, two Newton steps refine it (error < 1e-9 rad).
 *  Radii beyond r(max_theta) are extrapolated with the last slope. */
class PajdlaBaksteinInverse {
  public:
    explicit PajdlaBaksteinInverse(const core::PajdlaBaksteinCamera& camera);

    /// θ [rad] with r(θ) = radius_px.
    double thetaOfRadius(double radius_px) const;
    /// (φ, θ) [rad] of the ray seen at pixel uv.
    Eigen::Vector2d unproject(const Eigen::Vector2d& uv) const;
    /// Unit direction, in the camera frame, of the ray seen at pixel uv.
    Eigen::Vector3d rayOfPixel(const Eigen::Vector2d& uv) const;

    const core::PajdlaBaksteinCamera& camera() const { return m_camera; }

  private:
    core::PajdlaBaksteinCamera m_camera;
    std::vector<double> m_radius_table;  ///< r(θ_i), θ_i = i·m_step
    double m_step = 0;
};

}  // namespace mrpt_vslam::sim
