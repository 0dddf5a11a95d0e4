#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <mrpt_vslam/test/PlanarScene.h>
#include <mrpt_vslam/viewmap/ViewMapEKF.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

using mrpt::DEG2RAD;
using mrpt::math::TPose2D;
using mrpt_vslam::viewmap::predictViewObservation;
using mrpt_vslam::viewmap::TViewObservation;
using mrpt_vslam::viewmap::ViewMapEKF;
using mrpt_vslam::viewmap::viewObservationJacobians;
using mrpt_vslam::viewmap::test::angleError;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double uniform(std::mt19937& rng, double a, double b)
{
    return std::uniform_real_distribution<double>(a, b)(rng);
}

double gaussian(std::mt19937& rng, double sigma)
{
    return std::normal_distribution<double>(0, sigma)(rng);
}

/// A random positive definite N × N covariance with standard deviations of the order of `sigma`.
template <int N>
Eigen::Matrix<double, N, N> randomCovariance(std::mt19937& rng,
                                             const Eigen::Matrix<double, N, 1>& sigma)
{
    Eigen::Matrix<double, N, N> A;
    for (int i = 0; i < N * N; i++) A(i) = uniform(rng, -1, 1);
    const Eigen::Matrix<double, N, N> C =
        A * A.transpose() / N + 0.1 * Eigen::Matrix<double, N, N>::Identity();
    return sigma.asDiagonal() * C * sigma.asDiagonal();
}

Eigen::Matrix3d randomMotionCovariance(std::mt19937& rng)
{
    return randomCovariance<3>(rng, Eigen::Vector3d(0.02, 0.02, DEG2RAD(1.0)));
}

Eigen::Matrix2d randomObservationCovariance(std::mt19937& rng)
{
    return randomCovariance<2>(rng, Eigen::Vector2d(DEG2RAD(1.0), DEG2RAD(1.0)));
}

TPose2D randomIncrement(std::mt19937& rng)
{
    return {uniform(rng, 0.3, 0.6), uniform(rng, -0.1, 0.1), uniform(rng, -0.5, 0.5)};
}

/// Difference a − b of two poses with the angle wrapped.
Eigen::Vector3d poseError(const TPose2D& a, const TPose2D& b)
{
    return {a.x - b.x, a.y - b.y, angleError(a.phi, b.phi)};
}

/// Largest difference of two states, every third entry (a θ) wrapped.
double stateError(const Eigen::VectorXd& a, const Eigen::VectorXd& b)
{
    double e = 0;
    for (Eigen::Index i = 0; i < a.size(); i++) {
        e = std::max(e, std::abs(i % 3 == 2 ? angleError(a(i), b(i)) : a(i) - b(i)));
    }
    return e;
}

double maxAbs(const Eigen::MatrixXd& M) { return M.cwiseAbs().maxCoeff(); }

bool bitIdentical(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b)
{
    return a.rows() == b.rows() && a.cols() == b.cols() && (a.array() == b.array()).all();
}

/** A filter with `views` views whose blocks are all correlated: a random drive from a random
 *  start with a view every three steps, then one noisy observation of every view. */
ViewMapEKF randomFilter(std::mt19937& rng, size_t views)
{
    ViewMapEKF ekf(TPose2D(uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -M_PI, M_PI)),
                   randomCovariance<3>(rng, Eigen::Vector3d(0.05, 0.05, DEG2RAD(2.0))));
    for (size_t k = 0; k <= views; k++) {
        if (k > 0) ekf.addView();
        for (int step = 0; step < 3; step++) {
            ekf.predict(randomIncrement(rng), randomMotionCovariance(rng));
        }
    }
    for (size_t j = 0; j < views; j++) {
        const TViewObservation h = predictViewObservation(ekf.robotPose(), ekf.viewPose(j));
        const TViewObservation z{h.phi + gaussian(rng, DEG2RAD(1.0)),
                                 h.beta + gaussian(rng, DEG2RAD(1.0))};
        EXPECT_TRUE(ekf.update(j, z, randomObservationCovariance(rng), kInf).accepted);
    }
    return ekf;
}

/// Textbook EKF update with the full 2 × n Jacobian, dense gain and dense Joseph form.
struct TDenseUpdate {
    Eigen::VectorXd x;
    Eigen::MatrixXd P;
    Eigen::Vector2d nu;
    Eigen::Matrix2d S;
    double nis = 0;
};

TDenseUpdate denseUpdate(const ViewMapEKF& ekf, size_t view, const TViewObservation& z,
                         const Eigen::Matrix2d& R)
{
    const Eigen::VectorXd& x = ekf.mean();
    const Eigen::MatrixXd& P = ekf.covariance();
    const Eigen::Index n = x.size(), l = Eigen::Index(3 + 3 * view);
    const TViewObservation h = predictViewObservation(ekf.robotPose(), ekf.viewPose(view));
    const auto J = viewObservationJacobians(ekf.robotPose(), ekf.viewPose(view));
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, n);
    H.leftCols(3) = J.H_v;
    H.middleCols(l, 3) = J.H_l;
    TDenseUpdate d;
    d.nu = Eigen::Vector2d(angleError(z.phi, h.phi), angleError(z.beta, h.beta));
    d.S = H * P * H.transpose() + R;
    d.nis = d.nu.dot(d.S.inverse() * d.nu);
    const Eigen::MatrixXd K = P * H.transpose() * d.S.inverse();
    d.x = x + K * d.nu;
    const Eigen::MatrixXd IKH = Eigen::MatrixXd::Identity(n, n) - K * H;
    d.P = IKH * P * IKH.transpose() + K * R * K.transpose();
    return d;
}

}  // namespace

TEST(ViewMapEKF, PredictMatchesCompositionAndNumericJacobians)
{
    std::mt19937 rng(1);
    const double h = 1e-6;
    double max_mean = 0, max_vv = 0, max_vl = 0;
    for (int trial = 0; trial < 30; trial++) {
        ViewMapEKF ekf = randomFilter(rng, 3);
        const Eigen::VectorXd x0 = ekf.mean();
        const Eigen::MatrixXd P0 = ekf.covariance();
        const TPose2D pose0 = ekf.robotPose();
        const TPose2D u(uniform(rng, -0.5, 0.5), uniform(rng, -0.3, 0.3), uniform(rng, -2, 2));
        const Eigen::Matrix3d Q = randomMotionCovariance(rng);
        ekf.predict(u, Q);

        // Mean: x_v ⊕ u (MRPT's composition), views untouched.
        max_mean = std::max(max_mean, poseError(ekf.robotPose(), pose0 + u).cwiseAbs().maxCoeff());
        EXPECT_TRUE(bitIdentical(ekf.mean().tail(9), x0.tail(9)));

        // Central differences of f(x_v, u) = x_v ⊕ u with respect to x_v and u.
        Eigen::Matrix3d F_x, F_u;
        for (int i = 0; i < 3; i++) {
            TPose2D xp = pose0, xm = pose0, up = u, um = u;
            xp[i] += h;
            xm[i] -= h;
            up[i] += h;
            um[i] -= h;
            F_x.col(i) = poseError(xp + u, xm + u) / (2 * h);
            F_u.col(i) = poseError(pose0 + up, pose0 + um) / (2 * h);
        }
        const Eigen::MatrixXd& P = ekf.covariance();
        const Eigen::Matrix3d P_vv =
            F_x * P0.topLeftCorner(3, 3) * F_x.transpose() + F_u * Q * F_u.transpose();
        max_vv = std::max(max_vv, maxAbs(P.topLeftCorner(3, 3) - P_vv));
        max_vl = std::max(max_vl, maxAbs(P.topRightCorner(3, 9) - F_x * P0.topRightCorner(3, 9)));
        EXPECT_TRUE(bitIdentical(P.bottomLeftCorner(9, 3), P.topRightCorner(3, 9).transpose()));
        EXPECT_TRUE(bitIdentical(P.bottomRightCorner(9, 9), P0.bottomRightCorner(9, 9)));
        EXPECT_TRUE(bitIdentical(P, P.transpose()));
    }
    std::cout << "predict: max |mean − x⊕u| " << max_mean << ", max |P_vv − numeric| " << max_vv
              << ", max |P_vl − F_x P_vl| " << max_vl << "\n";
    EXPECT_LT(max_mean, 1e-12);
    EXPECT_LT(max_vv, 1e-7);
    EXPECT_LT(max_vl, 1e-7);
}

TEST(ViewMapEKF, AddViewClonesTheRobotExactly)
{
    std::mt19937 rng(2);
    double max_rel = 0, min_eig = kInf;
    for (int trial = 0; trial < 20; trial++) {
        ViewMapEKF ekf = randomFilter(rng, 2);
        const Eigen::VectorXd x0 = ekf.mean();
        const Eigen::MatrixXd P0 = ekf.covariance();
        const Eigen::Index n = x0.size();

        const size_t l = ekf.addView();
        ASSERT_EQ(l, 2u);
        ASSERT_EQ(ekf.viewCount(), 3u);
        const Eigen::VectorXd& x = ekf.mean();
        const Eigen::MatrixXd& P = ekf.covariance();
        EXPECT_TRUE(bitIdentical(x.head(n), x0));
        EXPECT_TRUE(bitIdentical(x.tail(3), x0.head(3)));
        EXPECT_TRUE(bitIdentical(P.topLeftCorner(n, n), P0));
        // Cloning: P_ll = P_vv, P_lv = P_vv, P_l,lj = P_v,lj (and the transposed blocks).
        const double scale = maxAbs(P0);
        max_rel = std::max({max_rel, maxAbs(P.block(n, n, 3, 3) - P0.topLeftCorner(3, 3)) / scale,
                            maxAbs(P.block(n, 0, 3, n) - P0.topRows(3)) / scale,
                            maxAbs(P.block(0, n, n, 3) - P0.leftCols(3)) / scale,
                            maxAbs(P - P.transpose()) / scale});
        min_eig =
            std::min(min_eig, Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(P).eigenvalues()(0));

        // The next prediction moves the robot away from its clone.
        const Eigen::Matrix3d P_new = ekf.viewCovariance(l), P_vv = ekf.robotCovariance();
        ekf.predict(randomIncrement(rng), randomMotionCovariance(rng));
        EXPECT_GT(maxAbs(ekf.robotCovariance() - P_vv), 1e-6);
        EXPECT_TRUE(bitIdentical(ekf.viewCovariance(l), P_new));
        EXPECT_TRUE(bitIdentical(ekf.mean().tail(3), x0.head(3)));
    }
    std::cout << "addView: max relative difference of the cloned blocks " << max_rel
              << ", smallest eigenvalue of P " << min_eig << "\n";
    EXPECT_LE(max_rel, 1e-15);
    EXPECT_GE(min_eig, -1e-12);
}

TEST(ViewMapEKF, UpdateMatchesDenseTextbookEKF)
{
    std::mt19937 rng(3);
    double max_x = 0, max_P = 0, max_nis = 0;
    for (int trial = 0; trial < 40; trial++) {
        const size_t views = 3 + size_t(trial % 2);
        ViewMapEKF ekf = randomFilter(rng, views);
        const size_t j = size_t(trial) % views;
        const Eigen::Matrix2d R = randomObservationCovariance(rng);
        const TViewObservation h = predictViewObservation(ekf.robotPose(), ekf.viewPose(j));
        // Shifted by −2π, 0 or 2π: the innovation must be wrapped.
        const double turn = 2 * M_PI * (trial % 3 - 1);
        const TViewObservation z{h.phi + gaussian(rng, DEG2RAD(2.0)) + turn,
                                 h.beta + gaussian(rng, DEG2RAD(2.0)) - turn};
        const TDenseUpdate dense = denseUpdate(ekf, j, z, R);

        const auto result = ekf.update(j, z, R, kInf);
        ASSERT_TRUE(result.accepted);
        EXPECT_LT(maxAbs(result.innovation - dense.nu), 1e-14);
        max_nis = std::max(max_nis, std::abs(result.nis - dense.nis) / dense.nis);
        max_x = std::max(max_x, stateError(ekf.mean(), dense.x));
        max_P = std::max(max_P, maxAbs(ekf.covariance() - dense.P));
        for (Eigen::Index i = 2; i < ekf.mean().size(); i += 3) {
            EXPECT_LE(std::abs(ekf.mean()(i)), M_PI);
        }
        EXPECT_TRUE(bitIdentical(ekf.covariance(), ekf.covariance().transpose()));
    }
    std::cout << "update vs dense EKF: max |Δx| " << max_x << ", max |ΔP| " << max_P
              << ", max relative ΔNIS " << max_nis << "\n";
    EXPECT_LT(max_x, 1e-10);
    EXPECT_LT(max_P, 1e-10);
    EXPECT_LT(max_nis, 1e-12);
}

TEST(ViewMapEKF, PredictionAndHypotheticalUpdateMatchTheDenseEKF)
{
    std::mt19937 rng(8);
    double max_S = 0, max_P = 0;
    for (int trial = 0; trial < 20; trial++) {
        ViewMapEKF ekf = randomFilter(rng, 4);
        const size_t j = size_t(trial) % 4;
        const Eigen::Matrix2d R = randomObservationCovariance(rng);
        const TViewObservation h = predictViewObservation(ekf.robotPose(), ekf.viewPose(j));
        const TDenseUpdate dense = denseUpdate(ekf, j, h, R);

        const auto predicted = ekf.predictObservation(j);
        EXPECT_EQ(predicted.z.phi, h.phi);
        EXPECT_EQ(predicted.z.beta, h.beta);
        max_S = std::max(max_S, maxAbs(predicted.HPHt + R - dense.S));
        const Eigen::MatrixXd before = ekf.covariance();
        const Eigen::Matrix3d P_vv = ekf.robotCovarianceAfterUpdates({{j, R}});
        EXPECT_TRUE(bitIdentical(before, ekf.covariance()));  // nothing applied
        max_P = std::max(max_P, maxAbs(P_vv - dense.P.topLeftCorner(3, 3)));

        // With a motion still to come: a zero-length prediction adds F_u Q F_uᵀ to P_vv only.
        const Eigen::Matrix3d Q = randomMotionCovariance(rng);
        const double c = std::cos(ekf.robotPose().phi), s = std::sin(ekf.robotPose().phi);
        Eigen::Matrix3d F_u;
        F_u << c, -s, 0, s, c, 0, 0, 0, 1;
        ViewMapEKF moved = ekf;
        moved.predict(TPose2D(0, 0, 0), Q);
        const TDenseUpdate after_motion = denseUpdate(moved, j, h, R);
        max_P = std::max(
            max_P, maxAbs(ekf.robotCovarianceAfterUpdates({{j, R}}, F_u * Q * F_u.transpose()) -
                          after_motion.P.topLeftCorner(3, 3)));
    }
    EXPECT_LT(max_S, 1e-12);
    EXPECT_LT(max_P, 1e-12);
    ViewMapEKF ekf = randomFilter(rng, 2);
    EXPECT_THROW(ekf.predictObservation(2), std::invalid_argument);
    EXPECT_THROW(ekf.robotCovarianceAfterUpdates({{0, Eigen::Matrix2d::Zero()}}),
                 std::invalid_argument);
    EXPECT_THROW(ekf.robotCovarianceAfterUpdates(
                     {{1, Eigen::Matrix2d::Identity()}, {1, Eigen::Matrix2d::Identity()}}),
                 std::invalid_argument);
}

TEST(ViewMapEKF, HypotheticalJointUpdateMatchesTheInformationForm)
{
    // Several views at once against the full-state information form
    // (P⁻¹ + Hᵀ R⁻¹ H)⁻¹ with the stacked H, with and without a motion still to come.
    std::mt19937 rng(9);
    double max_P = 0;
    for (int trial = 0; trial < 20; trial++) {
        ViewMapEKF ekf = randomFilter(rng, 5);
        if (trial % 2) ekf.predict(TPose2D(0, 0, 0), randomMotionCovariance(rng));
        std::vector<ViewMapEKF::THypotheticalObservation> obs;
        for (size_t j = size_t(trial) % 2; j < 5; j += 2)
            obs.push_back({j, randomObservationCovariance(rng)});
        const Eigen::Index n = ekf.mean().size(), m = Eigen::Index(obs.size());
        Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2 * m, n),
                        R_inv = Eigen::MatrixXd::Zero(2 * m, 2 * m);
        for (Eigen::Index k = 0; k < m; k++) {
            const auto J =
                viewObservationJacobians(ekf.robotPose(), ekf.viewPose(obs[size_t(k)].view));
            H.block(2 * k, 0, 2, 3) = J.H_v;
            H.block(2 * k, Eigen::Index(3 + 3 * obs[size_t(k)].view), 2, 3) = J.H_l;
            R_inv.block(2 * k, 2 * k, 2, 2) = obs[size_t(k)].R.inverse();
        }
        const Eigen::MatrixXd info = ekf.covariance().inverse() + H.transpose() * R_inv * H;
        max_P = std::max(max_P, maxAbs(ekf.robotCovarianceAfterUpdates(obs) -
                                       info.inverse().topLeftCorner(3, 3)));
    }
    std::cout << "joint hypothetical update vs information form: max |dP| " << max_P << "\n";
    EXPECT_LT(max_P, 1e-9);
}

TEST(ViewMapEKF, GatingRejectsOutliersAndKeepsTheFilter)
{
    std::mt19937 rng(4);
    for (int trial = 0; trial < 10; trial++) {
        ViewMapEKF ekf = randomFilter(rng, 3);
        const size_t j = size_t(trial) % 3;
        const Eigen::Matrix2d R = randomObservationCovariance(rng);
        const TViewObservation h = predictViewObservation(ekf.robotPose(), ekf.viewPose(j));
        const Eigen::Matrix2d S = denseUpdate(ekf, j, h, R).S;
        const double sigma_phi = std::sqrt(S(0, 0)), sigma_beta = std::sqrt(S(1, 1));
        ASSERT_LT(20 * sigma_phi, M_PI);
        const Eigen::VectorXd x0 = ekf.mean();
        const Eigen::MatrixXd P0 = ekf.covariance();

        // 20σ off in φ: NIS ≥ 20² whatever β, far above the 99 % gate.
        const TViewObservation outlier{h.phi + 20 * sigma_phi, h.beta};
        const double nis_outlier = denseUpdate(ekf, j, outlier, R).nis;
        const auto rejected = ekf.update(j, outlier, R, 9.21);
        EXPECT_FALSE(rejected.accepted);
        EXPECT_NEAR(rejected.nis, nis_outlier, 1e-12 * nis_outlier);
        EXPECT_GE(rejected.nis, 400 * (1 - 1e-12));
        EXPECT_TRUE(bitIdentical(ekf.mean(), x0));
        EXPECT_TRUE(bitIdentical(ekf.covariance(), P0));

        const TViewObservation inlier{h.phi + 0.5 * sigma_phi, h.beta - 0.5 * sigma_beta};
        const double nis_inlier = denseUpdate(ekf, j, inlier, R).nis;
        const auto accepted = ekf.update(j, inlier, R, 9.21);
        EXPECT_TRUE(accepted.accepted);
        EXPECT_NEAR(accepted.nis, nis_inlier, 1e-12 * nis_inlier);
        EXPECT_GT(maxAbs(ekf.mean() - x0), 0);
        if (trial == 0) {
            std::cout << "gating: NIS of the 20σ outlier " << rejected.nis
                      << " (rejected), of the 0.5σ observation " << accepted.nis << "\n";
        }
    }
}

TEST(ViewMapEKF, MonteCarloConsistencyAroundALoop)
{
    // 120 steps of 1/6 m around a 6 m × 4 m rectangle (sides of 36 and 24 steps, a 90° left turn
    // at the end of each), a view every 15 steps, every view within [0.3, 3] m observed.
    constexpr int kRuns = 50, kSteps = 120, kViewEvery = 15;
    const double kStep = 20.0 / kSteps;
    const Eigen::Vector3d q_sigma(0.01, 0.005, DEG2RAD(0.5));
    const Eigen::Vector2d r_sigma(DEG2RAD(1.0), DEG2RAD(1.0));
    const Eigen::Matrix3d Q = q_sigma.cwiseAbs2().asDiagonal();
    const Eigen::Matrix2d R = r_sigma.cwiseAbs2().asDiagonal();
    // Two-sided 95 % band of χ²₁₅₀ / 50: the ANEES of a consistent 3-dof estimate over 50 runs.
    const double band_low = 2.36, band_high = 3.72;

    std::mt19937 rng(2015);
    std::vector<double> anees(kSteps, 0.0);
    double final_slam = 0, final_odometry = 0;
    size_t accepted = 0, rejected = 0;
    for (int run = 0; run < kRuns; run++) {
        TPose2D truth(0, 0, 0);
        ViewMapEKF slam(truth), odometry(truth);
        std::vector<TPose2D> true_views;
        for (int step = 0; step < kSteps; step++) {
            if (step % kViewEvery == 0) {
                slam.addView();
                true_views.push_back(truth);
            }
            const int along = step % 60;
            const TPose2D u(kStep, 0, along == 35 || along == 59 ? M_PI / 2 : 0);
            truth = truth + u;
            const TPose2D measured(u.x + gaussian(rng, q_sigma.x()),
                                   u.y + gaussian(rng, q_sigma.y()),
                                   u.phi + gaussian(rng, q_sigma.z()));
            slam.predict(measured, Q);
            odometry.predict(measured, Q);
            for (size_t j = 0; j < true_views.size(); j++) {
                const double d = std::hypot(true_views[j].x - truth.x, true_views[j].y - truth.y);
                if (d < 0.3 || d > 3.0) continue;
                const TViewObservation h = predictViewObservation(truth, true_views[j]);
                const TViewObservation z{h.phi + gaussian(rng, r_sigma.x()),
                                         h.beta + gaussian(rng, r_sigma.y())};
                (slam.update(j, z, R, 9.21).accepted ? accepted : rejected)++;
            }
            anees[size_t(step)] += slam.robotNEES(truth) / kRuns;
        }
        const double s = std::sqrt(slam.robotCovariance().trace());
        const double o = std::sqrt(odometry.robotCovariance().trace());
        EXPECT_LT(s, o) << "run " << run;
        final_slam += s / kRuns;
        final_odometry += o / kRuns;
    }
    const auto inside = std::count_if(anees.begin(), anees.end(),
                                      [&](double a) { return a >= band_low && a <= band_high; });
    const double coverage = double(inside) / kSteps;
    std::cout << "Monte Carlo: ANEES in [" << band_low << ", " << band_high << "] on "
              << 100 * coverage << " % of the steps (range "
              << *std::min_element(anees.begin(), anees.end()) << " .. "
              << *std::max_element(anees.begin(), anees.end()) << ", mean "
              << std::accumulate(anees.begin(), anees.end(), 0.0) / kSteps << "); updates "
              << accepted << " accepted, " << rejected << " gated; final sqrt(trace P_vv) "
              << final_slam << " m with views, " << final_odometry << " m odometry only\n";
    EXPECT_GE(coverage, 0.9);
}

TEST(ViewMapEKF, BadArgumentsThrow)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Eigen::Matrix3d asymmetric = 0.01 * Eigen::Matrix3d::Identity();
    asymmetric(0, 1) = 0.005;
    const Eigen::Matrix3d indefinite = Eigen::Vector3d(0.01, 0.01, -1e-4).asDiagonal();
    EXPECT_THROW(ViewMapEKF bad(TPose2D(nan, 0, 0)), std::invalid_argument);
    EXPECT_THROW(ViewMapEKF bad(TPose2D(0, 0, kInf)), std::invalid_argument);
    EXPECT_THROW(ViewMapEKF bad(TPose2D(), asymmetric), std::invalid_argument);
    EXPECT_THROW(ViewMapEKF bad(TPose2D(), indefinite), std::invalid_argument);
    // P_vv = 0: the NEES is undefined.
    EXPECT_THROW(ViewMapEKF(TPose2D()).robotNEES(TPose2D()), std::domain_error);

    const Eigen::Matrix3d Q = 1e-4 * Eigen::Matrix3d::Identity();
    const Eigen::Matrix2d R = 1e-4 * Eigen::Matrix2d::Identity();
    ViewMapEKF ekf(TPose2D(), Q);
    ekf.addView();
    ekf.predict(TPose2D(1, 0, 0), Q);
    const Eigen::VectorXd x0 = ekf.mean();
    const Eigen::MatrixXd P0 = ekf.covariance();
    const TViewObservation z{0.1, 0.1};
    Eigen::Matrix2d R_asymmetric = R;
    R_asymmetric(0, 1) = 1e-5;

    EXPECT_THROW(ekf.predict(TPose2D(0, nan, 0), Q), std::invalid_argument);
    EXPECT_THROW(ekf.predict(TPose2D(1, 0, 0), asymmetric), std::invalid_argument);
    EXPECT_THROW(ekf.predict(TPose2D(1, 0, 0), indefinite), std::invalid_argument);
    EXPECT_THROW(ekf.update(1, z, R, 9.21), std::invalid_argument);
    EXPECT_THROW(ekf.update(0, TViewObservation{nan, 0}, R, 9.21), std::invalid_argument);
    EXPECT_THROW(ekf.update(0, TViewObservation{0, kInf}, R, 9.21), std::invalid_argument);
    EXPECT_THROW(ekf.update(0, z, Eigen::Matrix2d::Zero(), 9.21), std::invalid_argument);
    EXPECT_THROW(ekf.update(0, z, Eigen::Matrix2d(Eigen::Vector2d(1e-4, 0).asDiagonal()), 9.21),
                 std::invalid_argument);
    EXPECT_THROW(ekf.update(0, z, R_asymmetric, 9.21), std::invalid_argument);
    EXPECT_THROW(ekf.update(0, z, R, 0), std::invalid_argument);
    EXPECT_THROW(ekf.update(0, z, R, -1), std::invalid_argument);
    EXPECT_THROW(ekf.update(0, z, R, nan), std::invalid_argument);
    EXPECT_THROW(ekf.viewPose(1), std::invalid_argument);
    EXPECT_THROW(ekf.viewCovariance(1), std::invalid_argument);
    EXPECT_THROW(ekf.robotNEES(TPose2D(0, nan, 0)), std::invalid_argument);
    EXPECT_TRUE(bitIdentical(ekf.mean(), x0));
    EXPECT_TRUE(bitIdentical(ekf.covariance(), P0));

    // A singular but PSD Q is valid (e.g. no lateral slip).
    EXPECT_NO_THROW(ekf.predict(TPose2D(1, 0, 0), Eigen::Vector3d(1e-4, 0, 1e-4).asDiagonal()));
}
