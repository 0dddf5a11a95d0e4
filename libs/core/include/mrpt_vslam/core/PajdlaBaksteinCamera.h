#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint3D.h>

#include <Eigen/Core>

namespace mrpt_vslam::core {

/** Fisheye projection of Bakstein & Pajdla (2002), as used by Gamallo et al. (2013, Eq. 1):
 *
 *     r = a tan(θ / b) + c sin(θ / d)
 *     u = u0 + r cos φ
 *     v = β (v0 + r sin φ)
 *
 * φ is the azimuth of the ray around the optical axis (from the camera's +x axis towards +y) and
 * θ is its angle from the optical axis (+z). The paper calls θ the "elevation"; Eq. 1 only makes
 * sense with θ measured from the axis (r = 0 at the image centre), so that is what θ means here.
 * For an upward camera the elevation above the horizontal plane is π/2 − θ.
 *
 * Parameters are read from an `.ini` section (keys = member names, angles in degrees with `_deg`).
 */
class PajdlaBaksteinCamera : public mrpt::config::CLoadableOptions {
  public:
    /// @name Model parameters (Eq. 1)
    /// @{
    double a = 150.0;   ///< [px] tan-term gain
    double b = 2.5;     ///< [-] tan-term angle divisor
    double c = 180.0;   ///< [px] sin-term gain
    double d = 1.8;     ///< [-] sin-term angle divisor
    double u0 = 320.0;  ///< [px] image centre, column
    double v0 = 240.0;  ///< [px] image centre, row (before the β scaling)
    double beta = 1.0;  ///< [-] pixel aspect ratio (width / height)
    /// @}

    /// @name Image geometry
    /// @{
    int width = 640;                        ///< [px]
    int height = 480;                       ///< [px]
    double max_theta = 1.5533430342749532;  ///< [rad] field of view half-angle (ini: max_theta_deg)
    /// @}

    /// Image radius r(θ) [px] of Eq. 1.
    double radius(double theta) const;
    /// dr/dθ [px/rad].
    double radiusDerivative(double theta) const;
    /** [rad] The largest angle up to `theta_max` to which r(θ) increases: dr/dθ > 0 at 1001
     *  angles evenly over [0, that angle], as validate() checks it up to max_theta. */
    double increasingUpTo(double theta_max) const;

    /// Eq. 1: ray angles (φ, θ) [rad] → pixel (u, v) [px]. Does not check the image bounds.
    Eigen::Vector2d project(double phi, double theta) const;
    /// Jacobian ∂(u, v)/∂(φ, θ) of project().
    Eigen::Matrix2d projectJacobian(double phi, double theta) const;

    /// Whether θ is inside the field of view and the pixel (u, v) inside the image.
    bool isVisible(double phi, double theta) const;
    bool isInsideImage(const Eigen::Vector2d& uv) const;

    /// Ray angles (φ, θ) [rad] of a point given in the camera frame (z = optical axis).
    static Eigen::Vector2d anglesOfPoint(const mrpt::math::TPoint3D& point_in_camera);

    /// Checks that the parameters describe a valid, monotonic model; throws naming the key if not.
    void validate() const;

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                          const std::string& section) const override;
};

}  // namespace mrpt_vslam::core
