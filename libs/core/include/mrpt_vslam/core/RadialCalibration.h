#pragma once

#include <mrpt/img/TCamera.h>
#include <mrpt_vslam/core/ErrorMessage.h>

#include <Eigen/Core>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>

namespace mrpt_vslam::core {

/// A camera model fitted to a calibration, with its largest errors (RadialCalibration::fitted()).
template <class Model>
struct TCameraFit {
    Model camera;
    double max_error_px = 0;   ///< largest |r − fx ρ| over the field of view [px]
    double max_error_deg = 0;  ///< the largest error in θ it makes [deg]
};

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
 *  fieldOfView(), and fitted() completes the model with its largest errors. */
class RadialCalibration {
  public:
    /** \throw std::invalid_argument naming the problem: no focal lengths (fx, fy > 0), no image
     *  size, a value that is not finite, or tangential distortion (no radial model holds it). */
    explicit RadialCalibration(const mrpt::img::TCamera& calibration);

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
        /// Whether a model's slopes at the samples are at least half these: a flatter model
        /// would turn a pixel's error into a large error in θ.
        bool steepEnough(const Eigen::ArrayXd& model_slope) const
        {
            return (model_slope >= 0.5 * slope.array()).all();
        }
        /// The error of a fit in which no candidate `model` was steepEnough().
        std::invalid_argument noneSteepEnough(const std::string& model) const;
    };
    TSamples samples(double theta_max, int n) const;

    /** A model fitted to the calibration (`radius(camera, θ)`: its r(θ) [px]), with the image
     *  size set to the calibration's and the field of view to `theta_max`, its errors
     *  (errorOf()) and its check (`validate()`).
     *  \throw std::invalid_argument if the model is not valid. */
    template <class Model, class Radius>
    TCameraFit<Model> fitted(Model camera, double theta_max, const Radius& radius) const
    {
        camera.width = static_cast<int>(m_calibration.ncols);
        camera.height = static_cast<int>(m_calibration.nrows);
        camera.max_theta = theta_max;
        try {
            camera.validate();
        } catch (const std::exception& e) {
            throw std::invalid_argument("the fitted model is not valid: " + oneLineMessage(e));
        }
        const TError error =
            errorOf([&camera, &radius](double theta) { return radius(camera, theta); }, theta_max);
        return {camera, error.px, error.deg};
    }

  private:
    /// A model's largest errors against the calibration.
    struct TError {
        double px = 0;  ///< largest |r − fx ρ| [px]
        double deg = 0;  ///< largest error in θ it makes: θ' of r(θ') = fx ρ(θ), against θ [deg]
    };
    /// The errors of a model's radius r(θ) [px], increasing on [0, theta_max], over [0, theta_max].
    TError errorOf(const std::function<double(double)>& model_radius, double theta_max) const;

    mrpt::img::TCamera m_calibration;
};

}  // namespace mrpt_vslam::core
