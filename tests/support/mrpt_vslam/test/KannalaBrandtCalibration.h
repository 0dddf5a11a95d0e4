#pragma once

#include <mrpt/img/TCamera.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <functional>

namespace mrpt_vslam::test {

/** The Kannala-Brandt calibration of a radial camera whose radius at θ from the axis is
 *  `radius(θ)` [px], as a camera calibration would give it: f and f·k1..f·k4 by linear least
 *  squares on r(θ) = f (θ + k1 θ³ + k2 θ⁵ + k3 θ⁷ + k4 θ⁹) up to `max_theta` [rad]; square
 *  pixels, principal point (cx, cy). */
inline mrpt::img::TCamera kannalaBrandtCalibration(const std::function<double(double)>& radius,
                                                   double max_theta, uint32_t width,
                                                   uint32_t height, double cx, double cy)
{
    constexpr int kSamples = 200;
    Eigen::MatrixXd powers(kSamples, 5);
    Eigen::VectorXd r(kSamples);
    for (int i = 0; i < kSamples; i++) {
        const double theta = max_theta * (i + 1) / kSamples;
        for (int k = 0; k < 5; k++) powers(i, k) = std::pow(theta, 2 * k + 1);
        r[i] = radius(theta);
    }
    const Eigen::VectorXd fk = powers.colPivHouseholderQr().solve(r);
    mrpt::img::TCamera camera;
    camera.ncols = width;
    camera.nrows = height;
    camera.setIntrinsicParamsFromValues(fk[0], fk[0], cx, cy);
    camera.setDistortionKannalaBrandt(fk[1] / fk[0], fk[2] / fk[0], fk[3] / fk[0], fk[4] / fk[0]);
    return camera;
}

}  // namespace mrpt_vslam::test
