#pragma once

#include <mrpt/img/TCamera.h>
#include <mrpt_vslam/core/PajdlaBaksteinCamera.h>
#include <mrpt_vslam/core/RadialCalibration.h>

namespace mrpt_vslam::core {

using TPajdlaBaksteinFit = TCameraFit<PajdlaBaksteinCamera>;

/** The Pajdla-Bakstein model of PajdlaBaksteinCamera fitted by least squares to a camera
 *  calibration (RadialCalibration) up to `max_theta` [rad]: u0 = cx, β = fy / fx,
 *  v0 = cy / β, and r(θ) = a tan(θ / b) + c sin(θ / d) is fitted to fx ρ(θ) over the
 *  calibration's field of view (RadialCalibration::fieldOfView()): for given (b, d), a and c
 *  are linear least squares; (b, d) are searched on a grid and refined by a
 *  compass search (compassSearch()). Where the best model turns down before the edge of that
 *  field of view, it is fitted again over a narrower one, up to where it increased (by half
 *  at most): the fit's camera.max_theta.
 *  \throw std::invalid_argument naming the problem, for a calibration that RadialCalibration
 *  refuses, whose radius stops increasing within 5° of the axis, that no model follows
 *  with half its slope everywhere over the field of view (TSamples::noneSteepEnough()), or
 *  whose best model turns down within half of it. */
TPajdlaBaksteinFit fitPajdlaBakstein(const mrpt::img::TCamera& calibration, double max_theta);

}  // namespace mrpt_vslam::core
