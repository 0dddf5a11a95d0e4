#pragma once

#include <mrpt/img/TCamera.h>

#include <Eigen/Core>
#include <functional>

namespace mrpt_vslam::core {

/** A camera calibration in MRPT's form (`mrpt::img::TCamera`, as `camera-calib` and the
 *  grabbers store it in each `CObservationImage`) as a radial model: a ray at angle θ from the
 *  optical axis and azimuth φ lands at (cx + fx ρ(θ) cos φ, cy + fy ρ(θ) sin φ), with ρ by the
 *  calibration's distortion model:
 *  - `kannala_brandt` (OpenCV's fisheye model): ρ = θ (1 + k1 θ² + k2 θ⁴ + k3 θ⁶ + k4 θ⁸);
 *  - `none` (pinhole): ρ = tan θ;
 *  - `plumb_bob` with no tangential terms: ρ = t (1 + k1 t² + k2 t⁴ + k3 t⁶) /
 *    (1 + k4 t² + k5 t⁴ + k6 t⁶), t = tan θ.
 *  The project's camera models are radial too, with the same principal point and aspect
 *  fy / fx: fitPajdlaBakstein() and fitUnifiedSphere() fit their radius r(θ) to fx ρ(θ) over
 *  fieldOfView(), and errorOf() gives the fit's largest errors. */
class RadialCalibration {
  public:
    /** \throw std::invalid_argument naming the problem: no focal lengths (fx, fy > 0), no image
     *  size, a value that is not finite, or tangential distortion (no radial model holds it). */
    explicit RadialCalibration(const mrpt::img::TCamera& calibration);

    const mrpt::img::TCamera& calibration() const { return m_calibration; }
    /// ρ(θ) of the distortion model; NaN where it has none (the pinhole models at θ ≥ 90°).
    double normalizedRadius(double theta) const;
    /// [px] fx ρ(θ): the radius along the image's columns.
    double radius(double theta) const { return m_calibration.fx() * normalizedRadius(theta); }

    /** [rad] The largest angle up to `max_theta` at which ρ still increases and stays inside the
     *  image: its radius at most that of the farthest image corner (pixel centres at integers).
     *  \throw std::invalid_argument if that is less than 5°. */
    double fieldOfView(double max_theta) const;

    /// radius() and its slope dr/dθ at n angles evenly over (0, theta_max].
    struct TSamples {
        Eigen::VectorXd theta, radius, slope;
    };
    TSamples samples(double theta_max, int n) const;

    /// A model's largest errors against the calibration.
    struct TError {
        double px = 0;  ///< largest |r − fx ρ| [px]
        double deg = 0;  ///< largest error in θ it makes: θ' of r(θ') = fx ρ(θ), against θ [deg]
    };
    /// The errors of a model's radius r(θ) [px], increasing on [0, theta_max], over [0, theta_max].
    TError errorOf(const std::function<double(double)>& model_radius, double theta_max) const;

  private:
    mrpt::img::TCamera m_calibration;
};

/// A camera model fitted to a calibration, with its largest errors (RadialCalibration::TError).
template <class Model>
struct TCameraFit {
    Model camera;
    double max_error_px = 0;   ///< largest |r − fx ρ| over the field of view [px]
    double max_error_deg = 0;  ///< the largest error in θ it makes [deg]
};

}  // namespace mrpt_vslam::core
