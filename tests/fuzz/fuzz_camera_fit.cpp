// The camera fits on any calibration an image may carry (mrpt::img::TCamera): both models fitted
// by fitPajdlaBakstein() and fitUnifiedSphere(), or the calibration refused with
// std::invalid_argument. A fit returned with an error that is not finite, a crash or a hang is a
// bug. Bytes, front to back (FuzzInput): the distortion model (a word: none, plumb_bob,
// kannala_brandt), fx, fy, cx, cy (numbers), ncols, nrows (words), the eight distortion
// coefficients (numbers) and the largest angle asked of the fit (a word, 0.01 to π rad: the
// apps pass a validated [Camera] max_theta_deg).
#include <mrpt_vslam/core/PajdlaBaksteinFit.h>
#include <mrpt_vslam/core/UnifiedSphereFit.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>

#include "FuzzInput.h"

namespace {
template <class Fit>
void checkFinite(const Fit& fit)
{
    if (!std::isfinite(fit.max_error_px) || !std::isfinite(fit.max_error_deg)) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using mrpt::img::DistortionModel;
    mrpt_vslam::fuzz::FuzzInput in(data, size);
    mrpt::img::TCamera calibration;
    const DistortionModel models[] = {DistortionModel::none, DistortionModel::plumb_bob,
                                      DistortionModel::kannala_brandt};
    calibration.distortion = models[in.index(3)];
    calibration.fx(in.number());
    calibration.fy(in.number());
    calibration.cx(in.number());
    calibration.cy(in.number());
    calibration.ncols = in.word();
    calibration.nrows = in.word();
    for (double& k : calibration.dist) k = in.number();
    const double max_theta = in.finite(0.01, M_PI);
    try {
        checkFinite(mrpt_vslam::core::fitPajdlaBakstein(calibration, max_theta));
    } catch (const std::invalid_argument&) {
    }
    try {
        checkFinite(mrpt_vslam::core::fitUnifiedSphere(calibration, max_theta));
    } catch (const std::invalid_argument&) {
    }
    return 0;
}
