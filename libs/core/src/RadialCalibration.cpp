#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt_vslam/core/RadialCalibration.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mrpt_vslam::core {

RadialCalibration::RadialCalibration(const mrpt::img::TCamera& calibration)
    : m_calibration(calibration)
{
    const double fx = calibration.fx(), fy = calibration.fy();
    if (!(fx > 0 && fy > 0 && std::isfinite(fx) && std::isfinite(fy)))
        throw std::invalid_argument("the calibration has no focal lengths (fx, fy > 0)");
    if (calibration.ncols == 0 || calibration.nrows == 0)
        throw std::invalid_argument("the calibration has no image size (ncols, nrows)");
    if (!std::isfinite(calibration.cx()) || !std::isfinite(calibration.cy()))
        throw std::invalid_argument("the calibration's principal point is not finite");
    if (calibration.distortion == mrpt::img::DistortionModel::plumb_bob &&
        (calibration.p1() != 0 || calibration.p2() != 0))
        throw std::invalid_argument(
            "the calibration has tangential distortion (p1, p2), which no radial model holds");
    for (const double k : calibration.dist) {
        if (!std::isfinite(k))
            throw std::invalid_argument("the calibration's distortion is not finite");
    }
}

double RadialCalibration::normalizedRadius(double theta) const
{
    using mrpt::img::DistortionModel;
    const auto& c = m_calibration;
    if (c.distortion == DistortionModel::kannala_brandt) {
        const double t2 = theta * theta;
        return theta * (1 + t2 * (c.k1() + t2 * (c.k2() + t2 * (c.k3() + t2 * c.k4()))));
    }
    if (!(theta < M_PI / 2)) return std::numeric_limits<double>::quiet_NaN();
    const double t = std::tan(theta);
    if (c.distortion == DistortionModel::none) return t;
    const double t2 = t * t;
    const auto& k = c.dist;  // plumb_bob: k1 k2 p1 p2 k3 k4 k5 k6
    return t * (1 + t2 * (k[0] + t2 * (k[1] + t2 * k[4]))) /
           (1 + t2 * (k[5] + t2 * (k[6] + t2 * k[7])));
}

double RadialCalibration::fieldOfView(double max_theta) const
{
    const auto& c = m_calibration;
    const double beta = c.fy() / c.fx();
    double corner = 0;
    for (const double u : {-0.5, c.ncols - 0.5}) {
        for (const double v : {-0.5, c.nrows - 0.5})
            corner = std::max(corner, std::hypot(u - c.cx(), (v - c.cy()) / beta));
    }
    constexpr double kStep = 1e-3;  // [rad]
    double previous = 0, fov = max_theta;
    for (double theta = kStep; theta <= max_theta; theta += kStep) {
        const double r = radius(theta);
        if (!(r > previous) || r > corner) {
            fov = theta - kStep;
            break;
        }
        previous = r;
    }
    if (!(fov >= mrpt::DEG2RAD(5.0))) {
        throw std::invalid_argument(
            "the calibration's radius stops increasing, or leaves the image, within 5 deg of "
            "the optical axis");
    }
    return fov;
}

RadialCalibration::TSamples RadialCalibration::samples(double theta_max, int n) const
{
    TSamples s{Eigen::VectorXd(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
    constexpr double h = 1e-6;
    for (int i = 0; i < n; i++) {
        const double theta = theta_max * (i + 1) / n;
        s.theta[i] = theta;
        s.radius[i] = radius(theta);
        s.slope[i] = (radius(theta + h) - radius(theta - h)) / (2 * h);
    }
    return s;
}

std::invalid_argument RadialCalibration::TSamples::noneSteepEnough(const std::string& model) const
{
    return std::invalid_argument(mrpt::format(
        "no %s model has half the slope of the calibration's radius everywhere up to %.1f deg "
        "from the axis",
        model.c_str(), mrpt::RAD2DEG(theta[theta.size() - 1])));
}

RadialCalibration::TError RadialCalibration::errorOf(
    const std::function<double(double)>& model_radius, double theta_max) const
{
    TError error;
    constexpr int kChecks = 4000;
    for (int i = 0; i <= kChecks; i++) {
        const double theta = theta_max * i / kChecks;
        const double r = radius(theta);
        error.px = std::max(error.px, std::abs(model_radius(theta) - r));
        // the angle θ' the model gives the calibration's pixel, r(θ') = r, by bisection
        // (theta_max for a pixel beyond the model's field of view)
        double low = 0, high = theta_max;
        for (int k = 0; k < 60; k++) {
            const double mid = (low + high) / 2;
            (model_radius(mid) < r ? low : high) = mid;
        }
        error.deg = std::max(error.deg, mrpt::RAD2DEG(std::abs(high - theta)));
    }
    return error;
}

}  // namespace mrpt_vslam::core
