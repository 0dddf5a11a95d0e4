#pragma once

#include <mrpt/img/TCamera.h>
#include <mrpt_vslam/core/PajdlaBaksteinCamera.h>

namespace mrpt_vslam::core {

/** A camera calibration in MRPT's form (`mrpt::img::TCamera`, as `camera-calib` and the
 *  grabbers store it in each `CObservationImage`) as the Pajdla-Bakstein model of
 *  PajdlaBaksteinCamera, fitted by least squares.
 *
 *  Both models are radial: a ray at angle θ from the optical axis and azimuth φ lands at
 *  (cx + fx ρ(θ) cos φ, cy + fy ρ(θ) sin φ), with ρ by the calibration's distortion model:
 *  - `kannala_brandt` (OpenCV's fisheye model): ρ = θ (1 + k1 θ² + k2 θ⁴ + k3 θ⁶ + k4 θ⁸);
 *  - `none` (pinhole): ρ = tan θ;
 *  - `plumb_bob` with no tangential terms: ρ = t (1 + k1 t² + k2 t⁴ + k3 t⁶) /
 *    (1 + k4 t² + k5 t⁴ + k6 t⁶), t = tan θ.
 *  So u0 = cx, β = fy / fx, v0 = cy / β, and r(θ) = a tan(θ / b) + c sin(θ / d) is fitted to
 *  fx ρ(θ) on [0, max_theta]: for given (b, d), a and c are linear least squares; (b, d) are
 *  searched on a grid and refined. The field of view is the given max_theta, cut where ρ
 *  leaves the image (past its farthest corner) or stops increasing within it. */
struct TPajdlaBaksteinFit {
    PajdlaBaksteinCamera camera;
    double max_error_px = 0;   ///< largest |r − fx ρ| over the field of view [px]
    double max_error_deg = 0;  ///< the largest error in θ it makes [deg]
};

/** Fits the model to `calibration` up to `max_theta` [rad] (see TPajdlaBaksteinFit). Throws
 *  std::invalid_argument, naming the problem, for a calibration without focal lengths or image
 *  size, tangential distortion, or a ρ that stops increasing before 5° from the axis. */
TPajdlaBaksteinFit fitPajdlaBakstein(const mrpt::img::TCamera& calibration, double max_theta);

/** ρ(θ) of the calibration's distortion model (see TPajdlaBaksteinFit); NaN where it has no
 *  value (the pinhole models at θ ≥ 90°). */
double calibrationRadius(const mrpt::img::TCamera& calibration, double theta);

}  // namespace mrpt_vslam::core
