#include <mrpt/core/bits_math.h>
#include <mrpt_vslam/core/PajdlaBaksteinFit.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace mrpt_vslam::core {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The radii r_i = fx ρ(θ_i) to fit and their slopes dr/dθ, at θ_i evenly spread over
/// (0, max_theta].
struct TSamples {
    Eigen::VectorXd theta;
    Eigen::VectorXd radius;
    Eigen::VectorXd slope;
};

/// a, c of the least-squares fit for given b, d, and its sum of squared errors; infinite cost
/// where the tan term diverges or the model's slope falls below half the calibration's at a
/// sample (a flat model would turn a pixel's error into a large error in θ).
struct TLinearFit {
    double a = 0;
    double c = 0;
    double cost = std::numeric_limits<double>::infinity();
};

TLinearFit fitGains(const TSamples& s, double b, double d)
{
    TLinearFit fit;
    if (!(s.theta.maxCoeff() < b * M_PI / 2)) return fit;
    Eigen::MatrixX2d columns(s.theta.size(), 2);
    columns.col(0) = (s.theta / b).array().tan().matrix();
    columns.col(1) = (s.theta / d).array().sin().matrix();
    const Eigen::Vector2d gains = columns.completeOrthogonalDecomposition().solve(s.radius);
    const Eigen::ArrayXd slope = gains[0] / (b * (s.theta / b).array().cos().square()) +
                                 gains[1] / d * (s.theta / d).array().cos();
    if ((slope < 0.5 * s.slope.array()).any()) return fit;
    fit.a = gains[0];
    fit.c = gains[1];
    fit.cost = (columns * gains - s.radius).squaredNorm();
    return fit;
}

double focalRadius(const mrpt::img::TCamera& calibration, double theta)
{
    return calibration.fx() * calibrationRadius(calibration, theta);
}

/// The largest angle up to max_theta at which ρ still increases and stays inside the image:
/// its radius at most that of the farthest image corner (pixel centres at integers).
double fieldOfView(const mrpt::img::TCamera& calibration, double max_theta)
{
    const double beta = calibration.fy() / calibration.fx();
    double corner = 0;
    for (const double u : {-0.5, calibration.ncols - 0.5}) {
        for (const double v : {-0.5, calibration.nrows - 0.5}) {
            corner =
                std::max(corner, std::hypot(u - calibration.cx(), (v - calibration.cy()) / beta));
        }
    }
    constexpr double kStep = 1e-3;  // [rad]
    double previous = 0;
    for (double theta = kStep; theta <= max_theta; theta += kStep) {
        const double r = focalRadius(calibration, theta);
        if (!(r > previous) || r > corner) return theta - kStep;
        previous = r;
    }
    return max_theta;
}

}  // namespace

double calibrationRadius(const mrpt::img::TCamera& calibration, double theta)
{
    using mrpt::img::DistortionModel;
    if (calibration.distortion == DistortionModel::kannala_brandt) {
        const double t2 = theta * theta;
        return theta * (1 + t2 * (calibration.k1() +
                                  t2 * (calibration.k2() +
                                        t2 * (calibration.k3() + t2 * calibration.k4()))));
    }
    if (!(theta < M_PI / 2)) return kNaN;
    const double t = std::tan(theta);
    if (calibration.distortion == DistortionModel::none) return t;
    const double t2 = t * t;
    const auto& k = calibration.dist;  // plumb_bob: k1 k2 p1 p2 k3 k4 k5 k6
    return t * (1 + t2 * (k[0] + t2 * (k[1] + t2 * k[4]))) /
           (1 + t2 * (k[5] + t2 * (k[6] + t2 * k[7])));
}

TPajdlaBaksteinFit fitPajdlaBakstein(const mrpt::img::TCamera& calibration, double max_theta)
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

    const double theta_max = fieldOfView(calibration, max_theta);
    if (!(theta_max >= mrpt::DEG2RAD(5.0))) {
        throw std::invalid_argument(
            "the calibration's radius stops increasing, or leaves the image, within 5 deg of "
            "the optical axis");
    }
    constexpr int kSamples = 400;
    TSamples samples{Eigen::VectorXd(kSamples), Eigen::VectorXd(kSamples),
                     Eigen::VectorXd(kSamples)};
    for (int i = 0; i < kSamples; i++) {
        const double theta = theta_max * (i + 1) / kSamples, h = 1e-6;
        samples.theta[i] = theta;
        samples.radius[i] = focalRadius(calibration, theta);
        samples.slope[i] =
            (focalRadius(calibration, theta + h) - focalRadius(calibration, theta - h)) / (2 * h);
    }

    // (log b, log d): a grid, then a pattern search from its best point. Beyond 1e4 both
    // terms are linear in θ to 1e-9 of r; below d = 0.05, sin(θ / d) turns more than 30 times
    // over the field of view.
    const double log_b_min = std::log(theta_max * 2 / M_PI * 1.001), log_max = std::log(1e4);
    const double log_d_min = std::log(0.05);
    constexpr int kGrid = 80;
    const double step_b = (log_max - log_b_min) / (kGrid - 1);
    const double step_d = (log_max - log_d_min) / (kGrid - 1);
    std::array<double, 2> best{}, step{step_b, step_d};
    TLinearFit bestFit;
    const auto tryPoint = [&](double log_b, double log_d) {
        if (log_b < log_b_min || log_b > log_max || log_d < log_d_min || log_d > log_max)
            return false;
        const TLinearFit fit = fitGains(samples, std::exp(log_b), std::exp(log_d));
        if (!(fit.cost < bestFit.cost)) return false;
        bestFit = fit;
        best = {log_b, log_d};
        return true;
    };
    for (int i = 0; i < kGrid; i++) {
        for (int j = 0; j < kGrid; j++) tryPoint(log_b_min + i * step_b, log_d_min + j * step_d);
    }
    if (!std::isfinite(bestFit.cost)) {
        throw std::invalid_argument(
            "no increasing Pajdla-Bakstein model fits the calibration's radius");
    }
    while (std::max(step[0], step[1]) > 1e-9) {
        bool moved = false;
        for (int axis = 0; axis < 2; axis++) {
            for (const double sign : {1.0, -1.0}) {
                auto p = best;
                p[axis] += sign * step[axis];
                moved = tryPoint(p[0], p[1]) || moved;
            }
        }
        if (!moved) step = {step[0] / 2, step[1] / 2};
    }

    TPajdlaBaksteinFit result;
    PajdlaBaksteinCamera& camera = result.camera;
    camera.a = bestFit.a;
    camera.b = std::exp(best[0]);
    camera.c = bestFit.c;
    camera.d = std::exp(best[1]);
    camera.beta = fy / fx;
    camera.u0 = calibration.cx();
    camera.v0 = calibration.cy() / camera.beta;
    camera.width = static_cast<int>(calibration.ncols);
    camera.height = static_cast<int>(calibration.nrows);
    camera.max_theta = theta_max;
    constexpr int kChecks = 4000;
    for (int i = 0; i <= kChecks; i++) {
        const double theta = theta_max * i / kChecks;
        const double r = focalRadius(calibration, theta);
        result.max_error_px = std::max(result.max_error_px, std::abs(camera.radius(theta) - r));
        // the angle θ' the fitted model gives the calibration's pixel, r(θ') = r, by bisection
        // (max_theta for a pixel beyond the fitted field of view)
        double low = 0, high = theta_max;
        for (int k = 0; k < 60; k++) {
            const double mid = (low + high) / 2;
            (camera.radius(mid) < r ? low : high) = mid;
        }
        result.max_error_deg =
            std::max(result.max_error_deg, mrpt::RAD2DEG(std::abs(high - theta)));
    }
    try {
        camera.validate();
    } catch (const std::exception& e) {
        throw std::invalid_argument(std::string("the fitted model is not valid: ") + e.what());
    }
    return result;
}

}  // namespace mrpt_vslam::core
