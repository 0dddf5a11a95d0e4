#include <gtest/gtest.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/core/SensorPoseCorrection.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <vector>

using mrpt::math::TPose2D;
using mrpt_vslam::core::TEarlierPoseBearing;
using mrpt_vslam::core::TReadingPair;
using mrpt_vslam::core::TSensorPoseCorrection;

namespace {

/// δ⁻¹ ⊕ p
Eigen::Vector2d inverseCompose(const Eigen::Vector3d& d, const Eigen::Vector2d& p)
{
    const double c = std::cos(d[2]), s = std::sin(d[2]);
    const Eigen::Vector2d q = p - d.head<2>();
    return {c * q.x() + s * q.y(), -s * q.x() + c * q.y()};
}

/** A robot driving and turning among points read within 6 m, through a sensor whose pose on
 *  the robot is off by `error` and whose readings are `scale` times too short: the readings
 *  are (δ⁻¹ ⊕ (the point in the robot frame)) / k, so that the correction is δ = `error`,
 *  k = `scale`. Readings get N(0, σ_z²) per axis, each step's odometry N(0, Q) (σ_u per axis,
 *  `sigma_turn` [rad] on the turn, σ_u / 5 if not given), one draw for all the pairs of the
 *  step, or with `draw_per_pair` one per pair, as if each step read one point. With `circle`,
 *  the robot turns by the same each step. */
std::vector<TReadingPair> readingPairs(const Eigen::Vector3d& error, double sigma_z, double sigma_u,
                                       std::mt19937& rng, bool circle = false, double scale = 1,
                                       std::optional<double> sigma_turn = std::nullopt,
                                       bool draw_per_pair = false)
{
    std::normal_distribution<double> n(0, 1);
    std::vector<Eigen::Vector2d> points;
    for (int i = 0; i < 40; i++) points.emplace_back(-8 + 0.4 * i, i % 2 ? 3.0 : -3.0);
    const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * sigma_z * sigma_z;
    const double sigma_phi = sigma_turn.value_or(sigma_u / 5);
    const Eigen::Matrix3d Q =
        Eigen::Vector3d(sigma_u * sigma_u, sigma_u * sigma_u, sigma_phi * sigma_phi).asDiagonal();
    std::vector<TReadingPair> pairs;
    TPose2D x(-8, 0, 0);
    for (int k = 0; k < 80; k++) {
        // forward 0.2 m, turning left and right in turn, or always by the same
        const TPose2D u(0.2, 0, circle ? 0.08 : 0.15 * std::sin(0.3 * k));
        const TPose2D next = x + u;
        const auto odometry = [&] {
            return TPose2D(u.x + sigma_u * n(rng), u.y + sigma_u * n(rng),
                           u.phi + sigma_phi * n(rng));
        };
        const TPose2D stepOdometry = odometry();
        for (const auto& p : points) {
            const Eigen::Vector2d a = inverseCompose({x.x, x.y, x.phi}, p),
                                  b = inverseCompose({next.x, next.y, next.phi}, p);
            if (a.norm() > 6 || b.norm() > 6) continue;
            TReadingPair pair;
            pair.z_i = inverseCompose(error, a) / scale + sigma_z * Eigen::Vector2d(n(rng), n(rng));
            pair.z_j = inverseCompose(error, b) / scale + sigma_z * Eigen::Vector2d(n(rng), n(rng));
            pair.R_i = pair.R_j = R;
            pair.u = draw_per_pair ? odometry() : stepOdometry;
            pair.Q = Q;
            pair.step_i = draw_per_pair ? 2 * pairs.size() : k;
            pair.step_j = pair.step_i + 1;
            pairs.push_back(pair);
        }
        x = next;
    }
    return pairs;
}

/** The robot of readingPairs() (not on a circle) with a camera stated at (0.2, 0.05) on it,
 *  facing forward, and off by `error` (at δ ⊕ its stated pose): a view started every 6 steps,
 *  and its bearing read from 1 to 5 steps later in turn. Bearings get N(0, σ_b²), the odometry from
 *  the view N(0, Q) with Q growing with the steps between. */
std::vector<TEarlierPoseBearing> earlierPoseBearings(const Eigen::Vector3d& error, double sigma_b,
                                                     double sigma_u, std::mt19937& rng)
{
    std::normal_distribution<double> n(0, 1);
    const Eigen::Vector2d stated(0.2, 0.05);
    const double c = std::cos(error[2]), s = std::sin(error[2]);
    const Eigen::Vector2d camera(c * stated.x() - s * stated.y() + error[0],
                                 s * stated.x() + c * stated.y() + error[1]);
    std::vector<TPose2D> path{TPose2D(-8, 0, 0)};
    for (int k = 0; k < 400; k++)
        path.push_back(path.back() + TPose2D(0.2, 0, 0.15 * std::sin(0.3 * k)));
    std::vector<TEarlierPoseBearing> bearings;
    for (size_t i = 0, gap = 1; i + 6 < path.size(); i += 6, gap = gap % 5 + 1) {
        const TPose2D u = path[i + gap] - path[i];
        // the camera at x_i, seen from the camera at x_j, in x_j's frame
        const Eigen::Vector2d v = inverseCompose({u.x, u.y, u.phi}, camera) - camera;
        TEarlierPoseBearing b;
        b.sensor = stated;
        b.var = sigma_b * sigma_b;
        b.bearing = mrpt::math::wrapToPi(std::atan2(v.y(), v.x()) - error[2] + sigma_b * n(rng));
        const double su = sigma_u * std::sqrt(double(gap));
        b.Q = Eigen::Vector3d(su * su, su * su, std::pow(su / 5, 2)).asDiagonal();
        b.u = TPose2D(u.x + su * n(rng), u.y + su * n(rng), u.phi + su / 5 * n(rng));
        bearings.push_back(b);
    }
    return bearings;
}

/// Expects `c`, from `n` exact pairs or bearings, to be the pose error `error` and the scale
/// `scale` with none beyond 3 σ (the weak prior moves it by less than 1e-5).
void expectExact(const TSensorPoseCorrection& c, const Eigen::Vector3d& error, size_t n,
                 double scale = 1)
{
    EXPECT_NEAR(c.delta[0], error[0], 1e-4) << error.transpose();
    EXPECT_NEAR(c.delta[1], error[1], 1e-4) << error.transpose();
    EXPECT_NEAR(mrpt::math::wrapToPi(c.delta[2] - error[2]), 0, 1e-5) << error.transpose();
    EXPECT_NEAR(c.scale, scale, 1e-5) << error.transpose();
    EXPECT_EQ(c.outlier_pairs, 0u);
    EXPECT_EQ(c.pairs, n);
}

/// The sum of the squared normalised errors of `c` against `error` and, with `scale`, of its
/// scale, each expected within 4 σ.
double normalisedSquares(const TSensorPoseCorrection& c, const Eigen::Vector3d& error, int world,
                         std::optional<double> scale = std::nullopt)
{
    double sum = 0;
    for (int i = 0; i < 3; i++) {
        const double z = (c.delta[i] - error[i]) / std::sqrt(c.cov(i, i));
        EXPECT_LT(std::abs(z), 4) << "world " << world << ", component " << i;
        sum += z * z;
    }
    if (scale) {
        const double z = (c.scale - *scale) / c.scale_std;
        EXPECT_LT(std::abs(z), 4) << "world " << world << ", the scale";
        sum += z * z;
    }
    return sum;
}

}  // namespace

// Exact readings and odometry: the correction is the pose error, a half turn included, and the
// scale that of the readings (the weak prior moves them by less than 1e-5).
TEST(SensorPoseCorrection, RecoversThePoseErrorOfExactReadings)
{
    std::mt19937 rng(1);
    for (const auto& [error, scale] : {std::pair{Eigen::Vector3d(0, 0, 0), 1.0},
                                       {Eigen::Vector3d(0.3, -0.1, 0.1), 1.0},
                                       {Eigen::Vector3d(-0.05, 0.2, -0.5), 1.0},
                                       {Eigen::Vector3d(0.1, 0.1, M_PI - 0.05), 1.0},
                                       {Eigen::Vector3d(0, 0, 0), 1.1},
                                       {Eigen::Vector3d(0.3, -0.1, 0.1), 0.8}}) {
        const auto pairs = readingPairs(error, 0, 0, rng, false, scale);
        // exact data needs a covariance to weigh by
        auto weighed = pairs;
        for (auto& p : weighed) {
            p.R_i = p.R_j = Eigen::Matrix2d::Identity() * 1e-4;
            p.Q = Eigen::Matrix3d::Identity() * 1e-6;
        }
        ASSERT_GT(weighed.size(), 500u);
        const auto c = TSensorPoseCorrection::estimate(weighed);
        expectExact(c, error, weighed.size(), scale);
        EXPECT_TRUE(c.scaleTold());
        if (scale == 1) {  // the scale held at 1: the same pose error, and k not told
            const auto held = TSensorPoseCorrection::estimate(weighed, {}, 3, false);
            expectExact(held, error, weighed.size());
            EXPECT_FALSE(held.scaleTold());
        }
    }
}

// Exact bearings of the camera's earlier positions (a view-based map's observations) and
// exact odometry: the correction is the camera's pose error, a half turn included.
TEST(SensorPoseCorrection, RecoversTheCameraPoseErrorOfExactBearings)
{
    std::mt19937 rng(2);
    for (const Eigen::Vector3d& error :
         {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.2, -0.1, 0.1),
          Eigen::Vector3d(-0.3, 0.05, -0.4), Eigen::Vector3d(0.1, 0.1, M_PI - 0.05)}) {
        auto bearings = earlierPoseBearings(error, 0, 0, rng);
        for (auto& b : bearings) {
            b.var = 1e-6;
            b.Q = Eigen::Matrix3d::Identity() * 1e-8;
        }
        ASSERT_GT(bearings.size(), 60u);
        const auto c = TSensorPoseCorrection::estimate({}, bearings);
        expectExact(c, error, bearings.size());
        EXPECT_NEAR(c.scale_std, 1.0, 1e-9);  // bearings do not tell the scale: the prior's σ
    }
}

// Noisy bearings (1.5°) and odometry: over 30 worlds the normalised errors of the estimates
// have about unit variance.
TEST(SensorPoseCorrection, CovarianceMatchesTheSpreadOfTheEstimatesFromBearings)
{
    std::mt19937 rng(9);
    const Eigen::Vector3d error(0.1, -0.05, 0.05);
    double sumSquares = 0;
    const int worlds = 30;
    for (int w = 0; w < worlds; w++) {
        const auto c = TSensorPoseCorrection::estimate(
            {}, earlierPoseBearings(error, 1.5 * M_PI / 180, 0.01, rng));
        sumSquares += normalisedSquares(c, error, w);
    }
    const double variance = sumSquares / (3 * worlds);
    std::printf("bearings: normalised variance %.2f\n", variance);
    EXPECT_GT(variance, 0.4);
    EXPECT_LT(variance, 2.5);
}

// Noisy readings and odometry, the readings' noise or the odometry's the larger (each step's
// shared by the 9-21 pairs of that step), readings 5 % short: over 30 worlds each, each
// estimate lies within its own 4 σ of the error, and the normalised errors have about unit
// variance (the covariance is neither far too small nor too large; were the pairs of a step
// taken as independent, 8 with the odometry's noise the larger), the scale's alone too (with
// the expected Jacobian's gradient for k, 8: the scale came out 5 % too large); about 1 pair in
// 90 lies beyond 3 σ.
TEST(SensorPoseCorrection, CovarianceMatchesTheSpreadOfTheEstimates)
{
    std::mt19937 rng(7);
    const Eigen::Vector3d error(0.1, -0.05, 0.05);
    const double scale = 1.05;
    for (const auto& [sigma_z, sigma_u] : {std::pair{0.05, 0.01}, std::pair{0.02, 0.03}}) {
        double sumSquares = 0, scaleSquares = 0;
        size_t pairs = 0, outliers = 0;
        const int worlds = 30;
        for (int w = 0; w < worlds; w++) {
            const auto c = TSensorPoseCorrection::estimate(
                readingPairs(error, sigma_z, sigma_u, rng, false, scale));
            sumSquares += normalisedSquares(c, error, w, scale);
            scaleSquares += std::pow((c.scale - scale) / c.scale_std, 2);
            pairs += c.pairs;
            outliers += c.outlier_pairs;
        }
        const double variance = sumSquares / (4 * worlds), scaleVariance = scaleSquares / worlds;
        std::printf(
            "readings (sigma_z %.2f m, odometry %.2f m): normalised variance %.2f, of "
            "the scale alone %.2f\n",
            sigma_z, sigma_u, variance, scaleVariance);
        EXPECT_GT(variance, 0.4);
        EXPECT_LT(variance, 2.5);
        EXPECT_GT(scaleVariance, 0.4);
        EXPECT_LT(scaleVariance, 2.5);
        EXPECT_LT(static_cast<double>(outliers), 0.03 * static_cast<double>(pairs));
    }
}

// The odometry's turn about as noisy as the turns between readings (σ 0.05 rad against turns
// of up to 0.15 rad), each pair with its own odometry error as where each step reads one
// landmark: the turn enters the Jacobian of t as well as the residual (errors in variables).
// Over 30 worlds the mean of the normalised errors of t is within 0.5 of 0 (with the gradient
// of rᵀ C⁻¹ r at C fixed, 2.4 on t_y), those of θ and k within 1.5 (about 1 σ low, with
// either gradient), and their variance within 0.4 to 2.5 (1.5: the covariance is a little
// small here).
TEST(SensorPoseCorrection, NoisyTurnsDoNotBiasTheMove)
{
    std::mt19937 rng(11);
    const Eigen::Vector3d error(0.1, -0.05, 0.05);
    const double scale = 1.05;
    Eigen::Vector4d sum = Eigen::Vector4d::Zero(), sumSquares = Eigen::Vector4d::Zero();
    const int worlds = 30;
    for (int w = 0; w < worlds; w++) {
        const auto c = TSensorPoseCorrection::estimate(
            readingPairs(error, 0.05, 0.01, rng, false, scale, 0.05, true));
        Eigen::Vector4d z;
        for (int i = 0; i < 3; i++) z[i] = (c.delta[i] - error[i]) / std::sqrt(c.cov(i, i));
        z[3] = (c.scale - scale) / c.scale_std;
        sum += z;
        sumSquares += z.cwiseProduct(z);
    }
    const Eigen::Vector4d mean = sum / worlds;
    const double variance = sumSquares.sum() / (4 * worlds);
    std::printf("noisy turns: mean normalised errors %.2f %.2f %.2f %.2f, variance %.2f\n", mean[0],
                mean[1], mean[2], mean[3], variance);
    EXPECT_LT(std::abs(mean[0]), 0.5);
    EXPECT_LT(std::abs(mean[1]), 0.5);
    EXPECT_LT(std::abs(mean[2]), 1.5);
    EXPECT_LT(std::abs(mean[3]), 1.5);
    EXPECT_GT(variance, 0.4);
    EXPECT_LT(variance, 2.5);
}

// Readings through a sensor turned by a quarter turn from the pose given: all found, and most
// pairs beyond 3 σ at no correction.
TEST(SensorPoseCorrection, PairsDisagreeWithoutTheCorrection)
{
    std::mt19937 rng(3);
    const auto pairs = readingPairs({0, 0, M_PI / 2}, 0.05, 0.01, rng);
    const auto c = TSensorPoseCorrection::estimate(pairs);
    EXPECT_NEAR(c.delta[2], M_PI / 2, 4 * std::sqrt(c.cov(2, 2)));
    TSensorPoseCorrection none;
    size_t beyond = 0;
    for (const auto& p : pairs) beyond += none.whitenedResidual(p).norm() > 3;
    EXPECT_GT(beyond, pairs.size() / 2);
    EXPECT_LT(c.outlier_pairs, pairs.size() / 20);
}

// On a path of one curvature a turn of the sensor and a move along its path explain the same
// pairs: the turn's variance is many times what it would be were the move known; so does a
// scale of the readings with them. A path that turns both ways tells them apart.
TEST(SensorPoseCorrection, TurnConfoundingTellsCirclesFromVariedPaths)
{
    std::mt19937 rng(5);
    const auto varied = TSensorPoseCorrection::estimate(readingPairs({0, 0, 0}, 0.05, 0.01, rng));
    const auto circle =
        TSensorPoseCorrection::estimate(readingPairs({0, 0, 0}, 0.05, 0.01, rng, true));
    std::printf("turn confounding: varied path %.2f, circle %.2f; scale confounding: %.2f, %.2f\n",
                varied.turnConfounding(), circle.turnConfounding(), varied.scale_confounding,
                circle.scale_confounding);
    EXPECT_LT(varied.turnConfounding(), 2);
    EXPECT_GT(circle.turnConfounding(), 10);
    EXPECT_LT(varied.scale_confounding, 2);
    EXPECT_TRUE(varied.scaleTold());
    EXPECT_GT(circle.scale_confounding, 4);
    EXPECT_FALSE(circle.scaleTold());
    // the largest σ of the move against the eigenvalues of its covariance
    for (const auto& c : {varied, circle}) {
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(c.cov.topLeftCorner<2, 2>());
        EXPECT_NEAR(c.largestMoveStd(), std::sqrt(eig.eigenvalues().maxCoeff()), 1e-12);
    }
}

// On a circle readings shrunk to the sensor (k → 0) at the circle's centre explain every pair
// (the odometry then turns about that point): with the scale asked for, the path does not tell
// it from the move at the stated pose, so it is held at 1, and the fit stays on the ridge of
// turns and moves that fit the readings (few pairs beyond 3 σ, every figure finite), the
// odometry's noise stated 5 times as wide as drawn (a model made for poorer odometry). There
// full Gauss-Newton steps from the stated pose left the ridge: 255 of 828 pairs beyond 3 σ.
TEST(SensorPoseCorrection, CirclesHoldTheScaleAndStayOnTheRidge)
{
    std::mt19937 rng(17);
    for (const double sigma_u : {0.01, 0.002}) {
        auto pairs = readingPairs({0, 0, 0}, 0.05, sigma_u, rng, true);
        for (auto& p : pairs) p.Q *= 25;  // stated 5 times as wide as drawn
        const auto c = TSensorPoseCorrection::estimate(pairs);
        std::printf(
            "circle, odometry %.3f m: turn confounding %.0f, scale confounding %.0f, %zu "
            "of %zu pairs beyond 3 sigma\n",
            sigma_u, c.turnConfounding(), c.scale_confounding, c.outlier_pairs, c.pairs);
        EXPECT_EQ(c.scale, 1.0) << sigma_u;
        EXPECT_TRUE(std::isinf(c.scale_std)) << sigma_u;
        EXPECT_GT(c.scale_confounding, TSensorPoseCorrection::kToldScaleConfounding) << sigma_u;
        EXPECT_GT(c.turnConfounding(), 10) << sigma_u;
        EXPECT_TRUE(c.delta.allFinite() && c.cov.allFinite()) << sigma_u;
        EXPECT_LT(c.delta.head<2>().norm(), 5) << sigma_u;
        EXPECT_LT(static_cast<double>(c.outlier_pairs), 0.03 * static_cast<double>(c.pairs))
            << sigma_u;
    }
}

// A reading pairs with the same point's reading before it when that is at most max_gap steps
// back, through the odometry of the steps between them composed: mean a ⊕ b, covariance
// J_a Q_a J_aᵀ + J_b Q_b J_bᵀ.
TEST(ReadingPairing, PairsReadingsOfOnePointThroughTheOdometryBetween)
{
    std::vector<mrpt_vslam::core::TOdometryGaussian> motions(6);
    for (size_t s = 0; s < motions.size(); s++) {
        motions[s].mean = TPose2D(0.2 + 0.01 * s, 0.01, 0.1 * (s % 3));
        motions[s].cov = Eigen::Vector3d(1e-4 * (s + 1), 2e-4, 1e-5).asDiagonal();
    }
    mrpt_vslam::core::ReadingPairing<int> pairing(
        [&](int, size_t step) -> const mrpt_vslam::core::TOdometryGaussian& {
            return motions.at(step - 1);
        },
        2);
    const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * 0.01;
    EXPECT_FALSE(pairing.add(7, 1, {1, 2}, R));  // the point's first reading
    EXPECT_FALSE(pairing.add(8, 1, {3, 4}, R));
    const auto pair = pairing.add(7, 3, {1.5, 2.5}, R);
    ASSERT_TRUE(pair);
    EXPECT_EQ(pair->z_i, Eigen::Vector2d(1, 2));
    EXPECT_EQ(pair->z_j, Eigen::Vector2d(1.5, 2.5));
    EXPECT_EQ(pair->step_i, 1u);
    EXPECT_EQ(pair->step_j, 3u);
    // steps 2 and 3: motions[1] ⊕ motions[2]
    const TPose2D a = motions[1].mean, b = motions[2].mean;
    const TPose2D ab = a + b;
    EXPECT_NEAR(pair->u.x, ab.x, 1e-12);
    EXPECT_NEAR(pair->u.y, ab.y, 1e-12);
    EXPECT_NEAR(pair->u.phi, ab.phi, 1e-12);
    const double c = std::cos(a.phi), s = std::sin(a.phi);
    Eigen::Matrix3d Ja = Eigen::Matrix3d::Identity(), Jb = Eigen::Matrix3d::Identity();
    Ja(0, 2) = -s * b.x - c * b.y;
    Ja(1, 2) = c * b.x - s * b.y;
    Jb.topLeftCorner<2, 2>() << c, -s, s, c;
    const Eigen::Matrix3d Q =
        Ja * motions[1].cov * Ja.transpose() + Jb * motions[2].cov * Jb.transpose();
    EXPECT_LT((pair->Q - Q).cwiseAbs().maxCoeff(), 1e-12) << pair->Q << "\n" << Q;
    // three steps after the point's last reading: more than max_gap, no pair
    EXPECT_FALSE(pairing.add(8, 4, {3, 4}, R));
    EXPECT_TRUE(pairing.add(8, 5, {3, 4}, R));
}
