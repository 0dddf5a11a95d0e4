#include <mrpt_vslam/core/CompassSearch.h>
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

/// a, c of the least-squares fit for given b, d, and its sum of squared errors; infinite cost
/// where the tan term diverges or the model is not steep enough (TSamples::steepEnough()).
struct TLinearFit {
    double a = 0;
    double c = 0;
    double cost = std::numeric_limits<double>::infinity();
};

TLinearFit fitGains(const RadialCalibration::TSamples& s, double b, double d)
{
    TLinearFit fit;
    if (!(s.theta.maxCoeff() < b * M_PI / 2)) return fit;
    Eigen::MatrixX2d columns(s.theta.size(), 2);
    columns.col(0) = (s.theta / b).array().tan().matrix();
    columns.col(1) = (s.theta / d).array().sin().matrix();
    const Eigen::Vector2d gains = columns.completeOrthogonalDecomposition().solve(s.radius);
    const Eigen::ArrayXd slope = gains[0] / (b * (s.theta / b).array().cos().square()) +
                                 gains[1] / d * (s.theta / d).array().cos();
    if (!s.steepEnough(slope)) return fit;
    fit.a = gains[0];
    fit.c = gains[1];
    fit.cost = (columns * gains - s.radius).squaredNorm();
    return fit;
}

/// The model whose r(θ) fits the calibration best over (0, theta_max] (fitPajdlaBakstein()).
PajdlaBaksteinCamera fitOver(const RadialCalibration& radial, double theta_max)
{
    const RadialCalibration::TSamples samples = radial.samples(theta_max, 400);

    // (log b, log d): a grid, then a compass search from its best point. Beyond 1e4 both
    // terms are linear in θ to 1e-9 of r; below d = 0.05, sin(θ / d) turns more than 30 times
    // over the field of view.
    const double log_b_min = std::log(theta_max * 2 / M_PI * 1.001), log_max = std::log(1e4);
    const double log_d_min = std::log(0.05);
    constexpr int kGrid = 80;
    const double step_b = (log_max - log_b_min) / (kGrid - 1);
    const double step_d = (log_max - log_d_min) / (kGrid - 1);
    std::array<double, 2> best{};
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
        throw samples.noneSteepEnough("Pajdla-Bakstein");
    }
    compassSearch(best, {step_b, step_d}, 1e-9,
                  [&](const std::array<double, 2>& p) { return tryPoint(p[0], p[1]); });

    PajdlaBaksteinCamera camera;
    camera.a = bestFit.a;
    camera.b = std::exp(best[0]);
    camera.c = bestFit.c;
    camera.d = std::exp(best[1]);
    return camera;
}

}  // namespace

TPajdlaBaksteinFit fitPajdlaBakstein(const mrpt::img::TCamera& calibration, double max_theta)
{
    const RadialCalibration radial(calibration);
    double theta_max = radial.fieldOfView(max_theta);
    PajdlaBaksteinCamera camera = fitOver(radial, theta_max);
    // Where the calibration's radius flattens at the edge of the field of view (a barrel
    // pinhole), the best fit can turn down just before that edge: the field of view is then
    // narrowed to where the fit still increases, a few times and by half at most (a model that
    // turns down sooner is refused by fitted()).
    constexpr int kNarrowings = 5;
    constexpr double kMargin = 0.98;
    const double smallest = 0.5 * theta_max;
    for (int i = 0; i < kNarrowings; i++) {
        const double increasing = camera.increasingUpTo(theta_max);
        if (increasing == theta_max || kMargin * increasing < smallest) break;
        theta_max = kMargin * increasing;
        camera = fitOver(radial, theta_max);
    }
    camera.beta = calibration.fy() / calibration.fx();
    camera.u0 = calibration.cx();
    camera.v0 = calibration.cy() / camera.beta;
    return radial.fitted(camera, theta_max, [](const PajdlaBaksteinCamera& model, double theta) {
        return model.radius(theta);
    });
}

}  // namespace mrpt_vslam::core
