#include <mrpt_vslam/core/CompassSearch.h>
#include <mrpt_vslam/core/UnifiedSphereFit.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace mrpt_vslam::core {

namespace {

/// γ of the fit for a given ξ, and its largest error at the samples; infinite where the model
/// is not steep enough (TSamples::steepEnough()).
struct TGainFit {
    double gamma = 0;
    double cost = std::numeric_limits<double>::infinity();
};

TGainFit fitGain(const RadialCalibration::TSamples& s, double xi)
{
    const Eigen::ArrayXd cos = s.theta.array().cos();
    const Eigen::ArrayXd shape = s.theta.array().unaryExpr(
        [xi](double theta) { return UnifiedSphereCamera::normalizedRadius(theta, xi); });
    const auto largestError = [&](double gamma) {
        return (gamma * shape - s.radius.array()).abs().maxCoeff();
    };
    // The largest error is convex in γ: ternary search. Its minimum E* is at most E of the
    // least-squares gain, so at the sample of the largest shape s_k the best γ lies within
    // (r_k ± E) / s_k.
    const double ls = (shape * s.radius.array()).sum() / shape.square().sum();
    Eigen::Index k;
    const double s_k = shape.maxCoeff(&k), bound = largestError(ls);
    double low = (s.radius[k] - bound) / s_k, high = (s.radius[k] + bound) / s_k;
    for (int iteration = 0; iteration < 100; iteration++) {
        const double a = low + (high - low) / 3, b = high - (high - low) / 3;
        if (largestError(a) < largestError(b))
            high = b;
        else
            low = a;
    }
    const double gamma = (low + high) / 2;
    TGainFit fit;
    const Eigen::ArrayXd slope = gamma * (1 + xi * cos) / (cos + xi).square();
    if (!(gamma > 0) || !s.steepEnough(slope)) return fit;
    fit.gamma = gamma;
    fit.cost = largestError(gamma);
    return fit;
}

}  // namespace

TUnifiedSphereFit fitUnifiedSphere(const mrpt::img::TCamera& calibration, double max_theta)
{
    const RadialCalibration radial(calibration);
    const double theta_max = radial.fieldOfView(max_theta);
    const RadialCalibration::TSamples samples = radial.samples(theta_max, 400);

    // ξ as t = ξ / (1 + ξ) in [0, 1): one-to-one up to θ_max needs cos θ_max + ξ > 0 and
    // 1 + ξ cos θ_max > 0 (UnifiedSphereCamera::modelLimit()), kept with a margin; beyond
    // t = 0.999 (ξ = 999) the shape is sin θ to 1e-3.
    const double c = std::cos(theta_max);
    const double xi_low = std::max(0.0, -c) + 1e-6;
    const double xi_high = c < 0 ? std::min(999.0, -1 / c - 1e-6) : 999.0;
    const double t_low = xi_low / (1 + xi_low), t_high = xi_high / (1 + xi_high);
    double best_t = t_low;
    TGainFit best;
    const auto tryPoint = [&](double t) {
        if (t < t_low || t > t_high) return false;
        const TGainFit fit = fitGain(samples, t / (1 - t));
        if (!(fit.cost < best.cost)) return false;
        best = fit;
        best_t = t;
        return true;
    };
    constexpr int kGrid = 400;
    const double step = (t_high - t_low) / (kGrid - 1);
    for (int i = 0; i < kGrid; i++) tryPoint(t_low + i * step);
    if (!std::isfinite(best.cost)) {
        throw samples.noneSteepEnough("unified sphere");
    }
    compassSearch<1>({best_t}, {step}, 1e-12,
                     [&](const std::array<double, 1>& t) { return tryPoint(t[0]); });

    UnifiedSphereCamera camera;
    camera.xi = best_t / (1 - best_t);
    camera.fx = best.gamma;
    camera.fy = best.gamma * calibration.fy() / calibration.fx();
    camera.cx = calibration.cx();
    camera.cy = calibration.cy();
    camera.skew = 0;
    return radial.fitted(camera, theta_max, [](const UnifiedSphereCamera& model, double theta) {
        return model.fx * UnifiedSphereCamera::normalizedRadius(theta, model.xi);
    });
}

}  // namespace mrpt_vslam::core
