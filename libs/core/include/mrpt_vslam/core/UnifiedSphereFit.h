#pragma once

#include <mrpt/img/TCamera.h>
#include <mrpt_vslam/core/RadialCalibration.h>
#include <mrpt_vslam/core/UnifiedSphereCamera.h>

namespace mrpt_vslam::core {

using TUnifiedSphereFit = TCameraFit<UnifiedSphereCamera>;

/** The unified sphere model of UnifiedSphereCamera fitted to a camera calibration
 *  (RadialCalibration) up to `max_theta` [rad]: cx, cy as the calibration's, no skew, fy / fx
 *  as the calibration's, and r(θ) = γ sin θ / (cos θ + ξ), fx = γ, fitted to fx ρ(θ) over the
 *  calibration's field of view (RadialCalibration::fieldOfView()) with the least largest
 *  error: for a given ξ, γ by a ternary search (the largest error is convex in γ); ξ on a
 *  grid and refined by a compass search (compassSearch()), among the values whose model is
 *  one-to-one over the field of view (UnifiedSphereCamera::modelLimit()). The model has one
 *  shape parameter, so the largest error rather than the mean is what a user must know: it
 *  bounds every pixel's.
 *  \throw std::invalid_argument naming the problem, for a calibration that RadialCalibration
 *  refuses, whose radius stops increasing within 5° of the axis, or that no model follows
 *  with half its slope everywhere over the field of view (TSamples::noneSteepEnough()). */
TUnifiedSphereFit fitUnifiedSphere(const mrpt::img::TCamera& calibration, double max_theta);

}  // namespace mrpt_vslam::core
