#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <Eigen/Core>
#include <cmath>
#include <optional>

namespace mrpt_vslam::core {

/** Unified sphere model of a central catadioptric camera (Geyer & Daniilidis 2000; Mei & Rives,
 *  "Single View Point Omnidirectional Camera Calibration from Planar Grids", ICRA 2007), without
 *  lens distortion. A point X of the camera frame (z = optical axis) is
 *
 *   1. projected onto the unit sphere: X_s = X / |X| = (x_s, y_s, z_s);
 *   2. projected from the point (0, 0, −ξ) onto the normalised plane:
 *      m = (x_s / (z_s + ξ), y_s / (z_s + ξ));
 *   3. mapped to pixels by the generalised camera matrix:
 *      u = fx·m_x + skew·m_y + cx,  v = fy·m_y + cy.
 *
 *  ξ = 0 is a pinhole camera, ξ = 1 a parabolic mirror, 0 < ξ < 1 a hyperbolic or elliptic one
 *  (fx, fy are Mei's γ1, γ2: they include the mirror). At angle θ from the axis a ray lands at
 *  normalised radius ρ(θ) = sin θ / (cos θ + ξ); ρ grows with θ while 1 + ξ cos θ > 0 and
 *  cos θ + ξ > 0, i.e. up to θ_lim = acos(−min(ξ, 1/ξ)) (modelLimit()). The field of view
 *  max_theta must stay below it so that the model is one-to-one.
 *
 *  Inverse in closed form (Mei & Rives 2007): with r² = |m|²,
 *      η = (ξ + √(1 + (1 − ξ²) r²)) / (1 + r²),   X_s = (η m_x, η m_y, η − ξ),
 *  which has unit length.
 *
 *  For a camera under an upward mirror the image centre sees the camera itself, so +z of this
 *  model points down, towards the camera, and the horizon is at θ = 90°; the mounting rotation
 *  into the robot frame is not part of the model.
 *
 *  Pixel coordinates follow MRPT / OpenCV: (0, 0) is the centre of the top-left pixel.
 *  Parameters are read from an `.ini` section (keys = member names, the angle in degrees with
 *  `_deg`), see doc/camera-model.md.
 */
class UnifiedSphereCamera : public mrpt::config::CLoadableOptions {
  public:
    /// @name Model parameters
    /// @{
    double xi = 0.9;    ///< [-] ξ, distance of the projection centre from the sphere centre
    double fx = 110.0;  ///< [px] γ1, generalised focal length along the columns
    double fy = 110.0;  ///< [px] γ2, generalised focal length along the rows
    double cx = 320.0;  ///< [px] principal point, column
    double cy = 240.0;  ///< [px] principal point, row
    double skew = 0.0;  ///< [px] skew term of the camera matrix
    /// @}

    /// @name Image geometry
    /// @{
    int width = 640;                        ///< [px]
    int height = 480;                       ///< [px]
    double max_theta = 2.0943951023931957;  ///< [rad] largest angle from +z (ini: max_theta_deg)
    /// @}

    /** Pixel (u, v) of the direction `ray` (any length > 0) of the camera frame, or nullopt if
     *  the ray is more than max_theta from the axis or lands outside the image. */
    std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& ray) const;

    /** Jacobian ∂(u, v)/∂X of the projection of the point X (any length > 0, z_s + ξ > 0), without
     *  the field-of-view check. */
    Eigen::Matrix<double, 2, 3> projectJacobian(const Eigen::Vector3d& point) const;

    /** Unit ray of the pixel (u, v), in closed form; nullopt outside the image or when the ray
     *  is more than max_theta from the axis. */
    std::optional<Eigen::Vector3d> unproject(const Eigen::Vector2d& pixel) const;

    /// Whether (u, v) lies in [0, width − 1] × [0, height − 1].
    bool isInsideImage(const Eigen::Vector2d& uv) const;

    /// ρ(θ) = sin θ / (cos θ + ξ): the normalised radius of a ray at θ from the axis.
    static double normalizedRadius(double theta, double xi)
    {
        return std::sin(theta) / (std::cos(theta) + xi);
    }

    /// [rad] θ_lim = acos(−min(ξ, 1/ξ)): the largest field of view the model can represent.
    double modelLimit() const;

    /// Checks the parameters; throws std::invalid_argument naming the offending key if wrong.
    void validate() const;

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                          const std::string& section) const override;
};

}  // namespace mrpt_vslam::core
