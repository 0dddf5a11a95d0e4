#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/TrajectoryMetrics.h>

#include <cmath>

using namespace mrpt_vslam::core;
using mrpt::DEG2RAD;

namespace {

/// A curvy planar ground truth, 10 Hz.
TumTrajectory makeGroundTruth(size_t n = 50)
{
    TumTrajectory gt;
    for (size_t i = 0; i < n; i++) {
        const double t = 0.1 * i;
        gt.push_back(100 + t, {2 * std::cos(t), std::sin(2 * t), 0, mrpt::math::wrapToPi(t), 0, 0});
    }
    return gt;
}

/// Exact χ² CDF for an even number of dof: 1 - e^{-x/2} Σ_{k<n/2} (x/2)^k / k!.
double chi2CdfEven(double x, unsigned int n)
{
    double term = 1, sum = 1;
    for (unsigned int k = 1; k < n / 2; k++) sum += (term *= (x / 2) / k);
    return 1 - std::exp(-x / 2) * sum;
}

/// Exact χ² quantile for an even number of dof, by bisection.
double chi2QuantileEven(double p, unsigned int n)
{
    double lo = 0, hi = 10.0 * n + 100;
    for (int it = 0; it < 200; it++) {
        const double mid = (lo + hi) / 2;
        (chi2CdfEven(mid, n) < p ? lo : hi) = mid;
    }
    return lo;
}

}  // namespace

TEST(TrajectoryMetrics, ConstantOffsetGivesThatAte)
{
    const auto gt = makeGroundTruth();
    auto est = gt;
    for (auto& p : est.poses) {
        p.x += 0.3;
        p.y -= 0.4;
    }
    const auto m = evaluateTrajectory(est, gt);
    EXPECT_EQ(m.matchedPoses(), gt.size());
    EXPECT_NEAR(m.ate_rmse, 0.5, 1e-12);
    EXPECT_NEAR(m.ate_mean, 0.5, 1e-12);
    EXPECT_NEAR(m.ate_max, 0.5, 1e-12);
    EXPECT_NEAR(m.heading_rmse, 0, 1e-12);
    EXPECT_DOUBLE_EQ(m.heading_share_under_threshold, 1.0);
    // Aligned: a pure translation is removed entirely.
    TTrajectoryMetricsOptions opts;
    opts.align_se2 = true;
    const auto a = evaluateTrajectory(est, gt, opts);
    EXPECT_NEAR(a.ate_max, 0, 1e-9);
    EXPECT_NEAR(a.alignment.x, -0.3, 1e-9);
    EXPECT_NEAR(a.alignment.y, 0.4, 1e-9);
}

// `after`: only the poses later than that time count; the earlier ones (here 1 m off) do not.
TEST(TrajectoryMetrics, OnlyPosesAfterTheGivenTimeCount)
{
    const auto gt = makeGroundTruth();
    auto est = gt;
    for (size_t i = 0; i < est.size(); i++) est.poses[i].x += est.timestamps[i] <= 102 ? 1.0 : 0.1;
    TTrajectoryMetricsOptions opts;
    opts.after = 102;
    const auto m = evaluateTrajectory(est, gt, opts);
    EXPECT_EQ(m.estimate_poses, 29u);  // t = 102.1 to 104.9
    EXPECT_EQ(m.matchedPoses(), 29u);
    EXPECT_GT(m.timestamps.front(), 102);
    EXPECT_NEAR(m.ate_max, 0.1, 1e-9);
    EXPECT_NEAR(evaluateTrajectory(est, gt).ate_max, 1.0, 1e-9);  // all poses by default
    opts.after = 105;
    EXPECT_THROW(evaluateTrajectory(est, gt, opts), std::runtime_error);  // none left
}

TEST(TrajectoryMetrics, RigidlyMovedCopyAlignsToZero)
{
    const auto gt = makeGroundTruth();
    const mrpt::math::TPose2D moved{1.0, -2.0, DEG2RAD(30.0)};
    TumTrajectory est;
    for (size_t i = 0; i < gt.size(); i++)
        est.push_back(gt.timestamps[i], applySE2(moved, gt.poses[i]));

    TTrajectoryMetricsOptions opts;
    const auto raw = evaluateTrajectory(est, gt, opts);
    // Unaligned heading error is exactly the rotation; position errors are |R p + t - p|.
    EXPECT_NEAR(raw.heading_max, DEG2RAD(30.0), 1e-9);
    EXPECT_NEAR(raw.heading_mean, DEG2RAD(30.0), 1e-9);
    EXPECT_DOUBLE_EQ(raw.heading_share_under_threshold, 0.0);
    const auto p0 = applySE2(moved, gt.poses[0]);
    EXPECT_NEAR(raw.position_errors[0], std::hypot(p0.x - gt.poses[0].x, p0.y - gt.poses[0].y),
                1e-12);

    opts.align_se2 = true;
    const auto al = evaluateTrajectory(est, gt, opts);
    EXPECT_NEAR(al.ate_max, 0, 1e-9);
    EXPECT_NEAR(al.heading_max, 0, 1e-9);
    // The alignment is the inverse of the applied motion.
    const auto back = applySE2(al.alignment, applySE2(moved, {3, 4, 0, 0.2, 0, 0}));
    EXPECT_NEAR(back.x, 3, 1e-9);
    EXPECT_NEAR(back.y, 4, 1e-9);
    EXPECT_NEAR(back.yaw, 0.2, 1e-9);
}

TEST(TrajectoryMetrics, AlignmentMatchesBruteForceOnNoisyPoints)
{
    auto& rng = mrpt::random::getRandomGenerator();
    rng.randomize(1234);
    std::vector<mrpt::math::TPoint2D> a, b;
    for (int i = 0; i < 30; i++) {
        a.emplace_back(rng.drawUniform(-5, 5), rng.drawUniform(-5, 5));
        const double c = std::cos(0.7), s = std::sin(0.7);
        b.emplace_back(c * a.back().x - s * a.back().y + 2 + rng.drawGaussian1D(0, 0.1),
                       s * a.back().x + c * a.back().y - 1 + rng.drawGaussian1D(0, 0.1));
    }
    const auto cost = [&](const mrpt::math::TPose2D& T) {
        double sum = 0;
        for (size_t i = 0; i < a.size(); i++) {
            const auto p = applySE2(T, {a[i].x, a[i].y, 0, 0, 0, 0});
            sum += std::pow(p.x - b[i].x, 2) + std::pow(p.y - b[i].y, 2);
        }
        return sum;
    };
    const auto best = alignSE2(a, b);
    const double c0 = cost(best);
    // Any perturbation of the closed-form optimum costs more.
    for (double d : {-1e-3, 1e-3}) {
        EXPECT_GT(cost({best.x + d, best.y, best.phi}), c0);
        EXPECT_GT(cost({best.x, best.y + d, best.phi}), c0);
        EXPECT_GT(cost({best.x, best.y, best.phi + d}), c0);
    }
    EXPECT_NEAR(best.phi, 0.7, 0.02);
}

TEST(TrajectoryMetrics, HeadingErrorWrapsAtPi)
{
    TumTrajectory gt, est;
    gt.push_back(1, {0, 0, 0, DEG2RAD(179.0), 0, 0});
    est.push_back(1, {0, 0, 0, DEG2RAD(-179.0), 0, 0});
    gt.push_back(2, {0, 0, 0, DEG2RAD(-178.0), 0, 0});
    est.push_back(2, {0, 0, 0, DEG2RAD(178.0), 0, 0});
    const auto m = evaluateTrajectory(est, gt);
    EXPECT_NEAR(m.heading_errors[0], DEG2RAD(2.0), 1e-12);
    EXPECT_NEAR(m.heading_errors[1], DEG2RAD(-4.0), 1e-12);
    EXPECT_NEAR(m.heading_max, DEG2RAD(4.0), 1e-12);
    EXPECT_NEAR(m.heading_mean, DEG2RAD(3.0), 1e-12);
    EXPECT_NEAR(m.heading_rmse, DEG2RAD(std::sqrt(10.0)), 1e-12);
    EXPECT_DOUBLE_EQ(m.heading_share_under_threshold, 1.0);
}

TEST(TrajectoryMetrics, AssociatesByNearestTimeWithinTolerance)
{
    TumTrajectory gt, est;
    for (int i = 0; i < 5; i++) gt.push_back(i, {static_cast<double>(i), 0, 0, 0, 0, 0});
    est.push_back(0.02, {0, 1, 0, 0, 0, 0});  // matches gt 0, error 1
    est.push_back(1.5, {0, 0, 0, 0, 0, 0});   // no gt within 0.05 s
    est.push_back(2.96, {3, 2, 0, 0, 0, 0});  // matches gt 3, error 2
    const auto pairs = associateByTime(est, gt, 0.05);
    ASSERT_EQ(pairs.size(), 2u);
    EXPECT_EQ(pairs[0], std::make_pair(size_t{0}, size_t{0}));
    EXPECT_EQ(pairs[1], std::make_pair(size_t{2}, size_t{3}));
    const auto m = evaluateTrajectory(est, gt);
    EXPECT_EQ(m.estimate_poses, 3u);
    EXPECT_EQ(m.matchedPoses(), 2u);
    EXPECT_NEAR(m.ate_mean, 1.5, 1e-12);
    EXPECT_NEAR(m.ate_rmse, std::sqrt(2.5), 1e-12);
    EXPECT_NEAR(m.ate_max, 2.0, 1e-12);
    TumTrajectory far;
    far.push_back(10, {});
    EXPECT_THROW(evaluateTrajectory(far, gt), std::runtime_error);
}

TEST(TrajectoryMetrics, RefusesAnEstimateThatHardlyOverlapsTheGroundTruth)
{
    // Another run's ground truth sharing one timestamp with a 10-pose estimate: 1 of 10 matched.
    TumTrajectory gt, est;
    for (int i = 0; i < 10; i++) est.push_back(i, {});
    for (int i = 9; i < 20; i++) gt.push_back(i, {});
    try {
        evaluateTrajectory(est, gt);
        FAIL() << "scored an estimate with 1 of 10 poses matched";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("1 of 10 estimated poses"), std::string::npos)
            << e.what();
    }
    // Half of the poses matched is enough (the default share), and the share is an option.
    TumTrajectory half;
    for (int i = 4; i < 14; i++) half.push_back(i, {});
    EXPECT_EQ(evaluateTrajectory(half, gt).matchedPoses(), 5u) << "5 of 10 must be scored";
    TTrajectoryMetricsOptions strict;
    strict.min_matched_share = 0.6;
    EXPECT_THROW(evaluateTrajectory(half, gt, strict), std::runtime_error);
}

TEST(TrajectoryMetrics, NeesOfKnownErrorAndCovariance)
{
    // e = (1, 2), P = diag(4, 1): NEES = 1/4 + 4/1.
    EXPECT_NEAR(nees(Eigen::Vector2d(1, 2), Eigen::Matrix2d(Eigen::Vector2d(4, 1).asDiagonal())),
                4.25, 1e-12);
    // Correlated: P = [[2,1],[1,2]], P^-1 = [[2,-1],[-1,2]]/3, e = (1,1): NEES = 2/3.
    Eigen::Matrix2d P;
    P << 2, 1, 1, 2;
    EXPECT_NEAR(nees(Eigen::Vector2d(1, 1), P), 2.0 / 3, 1e-12);
    // Planar pose, heading wrapped: Δφ = 2°.
    const Eigen::Matrix3d C = Eigen::Vector3d(0.01, 0.04, std::pow(DEG2RAD(1.0), 2)).asDiagonal();
    const double n2 = poseNEES(mrpt::math::TPose2D{0.1, 0.2, DEG2RAD(179.0)},
                               mrpt::math::TPose2D{0, 0, DEG2RAD(-179.0)}, C);
    EXPECT_NEAR(n2, 1 + 1 + 4, 1e-9);
    Eigen::Matrix<double, 6, 6> C6 = Eigen::Matrix<double, 6, 6>::Identity();
    C6(2, 2) = 0.25;
    const double n3 = poseNEES(mrpt::math::TPose3D{1, 0, 0.5, 0, 0, 0.1},
                               mrpt::math::TPose3D{0, 0, 0, 0, 0, 0}, C6);
    EXPECT_NEAR(n3, 1 + 1 + 0.01, 1e-12);
    EXPECT_THROW(nees(Eigen::Vector2d(1, 1), Eigen::Matrix3d::Identity()), std::invalid_argument);
    EXPECT_THROW(nees(Eigen::Vector2d(1, 1), Eigen::Matrix2d::Zero()), std::invalid_argument);
}

TEST(TrajectoryMetrics, Chi2BoundsMatchExactQuantiles)
{
    // Large dof (averaged over 50 runs of a 2-dof error): close to the exact quantiles.
    const auto [lo, hi] = chi2Bounds(2, 0.95, 50);
    EXPECT_NEAR(lo, chi2QuantileEven(0.025, 100) / 50, 0.002 * lo);
    EXPECT_NEAR(hi, chi2QuantileEven(0.975, 100) / 50, 0.002 * hi);
    EXPECT_LT(lo, 2.0);
    EXPECT_GT(hi, 2.0);
    // One run of 2 dof: the upper quantile is -2 ln(0.025) = 7.378 (1% approximation).
    const auto one = chi2Bounds(2);
    EXPECT_NEAR(one.second, -2 * std::log(0.025), 0.01 * 7.378);
    EXPECT_GE(one.first, 0.0);
    EXPECT_GE(chi2Bounds(1).first, 0.0);
    EXPECT_THROW(chi2Bounds(0), std::invalid_argument);
    EXPECT_THROW(chi2Bounds(3, 1.0), std::invalid_argument);
}
