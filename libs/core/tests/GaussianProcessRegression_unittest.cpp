#include <gtest/gtest.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/GaussianProcessRegression.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <stdexcept>

using mrpt_vslam::core::GaussianProcessRegression;
using THyper = GaussianProcessRegression::THyperParameters;

namespace {

const double kLog2PiE = std::log(2 * M_PI) + 1.0;  // log(2πe)

Eigen::MatrixXd uniformPoints(int n, int dim, double lo, double hi, unsigned seed)
{
    mrpt::random::CRandomGenerator rng(seed);
    Eigen::MatrixXd X(n, dim);
    for (int i = 0; i < n; i++) {
        for (int d = 0; d < dim; d++) X(i, d) = rng.drawUniform(lo, hi);
    }
    return X;
}

/// Explicit K(A, B) of the squared-exponential kernel.
Eigen::MatrixXd seKernel(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const THyper& h)
{
    Eigen::MatrixXd K(A.rows(), B.rows());
    for (int i = 0; i < A.rows(); i++) {
        for (int j = 0; j < B.rows(); j++) {
            const double r2 = (A.row(i) - B.row(j)).squaredNorm();
            K(i, j) =
                h.signal_std * h.signal_std * std::exp(-r2 / (2 * h.length_scale * h.length_scale));
        }
    }
    return K;
}

/// Targets drawn from the GP prior with hyperparameters h: y = chol(K + σ_n² I) z.
Eigen::VectorXd sampleGp(const Eigen::MatrixXd& X, const THyper& h, unsigned seed)
{
    Eigen::MatrixXd K = seKernel(X, X, h);
    K.diagonal().array() += h.noise_std * h.noise_std;
    mrpt::random::CRandomGenerator rng(seed);
    Eigen::VectorXd z(X.rows());
    for (int i = 0; i < X.rows(); i++) z[i] = rng.drawGaussian1D(0.0, 1.0);
    return Eigen::LLT<Eigen::MatrixXd>(K).matrixL() * z;
}

}  // namespace

TEST(GaussianProcessRegression, OneTrainingPointMatchesClosedForm)
{
    const THyper h{0.8, 1.3, 0.2};
    GaussianProcessRegression gp(h);
    Eigen::MatrixXd X(1, 2);
    X << 0.3, -0.2;
    gp.fit(X, Eigen::VectorXd::Constant(1, 1.7));
    const double sf2 = 1.69, sn2 = 0.04;
    Eigen::MatrixXd Q(3, 2);
    Q << 0.3, -0.2, 1.0, 0.5, -0.4, 0.9;
    const auto latent = gp.predict(Q);
    const auto noisy = gp.predict(Q, true);
    for (int i = 0; i < 3; i++) {
        const double k = sf2 * std::exp(-(Q.row(i) - X.row(0)).squaredNorm() / (2 * 0.64));
        // mean = k y / (σ_f² + σ_n²),  var = σ_f² − k² / (σ_f² + σ_n²)
        EXPECT_NEAR(latent.mean[i], k * 1.7 / (sf2 + sn2), 1e-12);
        EXPECT_NEAR(latent.variance[i], sf2 - k * k / (sf2 + sn2), 1e-12);
        EXPECT_NEAR(noisy.variance[i], sf2 - k * k / (sf2 + sn2) + sn2, 1e-12);
        EXPECT_DOUBLE_EQ(noisy.mean[i], latent.mean[i]);
    }
    // At the training point: σ_f² σ_n² / (σ_f² + σ_n²).
    EXPECT_NEAR(latent.variance[0], sf2 * sn2 / (sf2 + sn2), 1e-12);
    EXPECT_NEAR(gp.kernel(Q.row(1).transpose(), X.row(0).transpose()),
                sf2 * std::exp(-(0.49 + 0.49) / 1.28), 1e-12);
}

TEST(GaussianProcessRegression, InterpolatesAsNoiseVanishes)
{
    // Inputs 1.5ℓ apart (well conditioned K).
    Eigen::MatrixXd X(8, 1);
    X << 0.0, 1.5, 3.0, 4.5, 6.0, 7.5, 9.0, 10.5;
    Eigen::VectorXd y(8);
    y << 0.5, -1.0, 2.0, 0.3, 1.1, -0.7, 0.0, 1.5;
    double previous_error = 1.0;
    for (const double sigma_n : {1e-2, 1e-3, 1e-4}) {
        GaussianProcessRegression gp(THyper{1.0, 1.0, sigma_n});
        gp.fit(X, y);
        const auto p = gp.predict(X);
        // y − f̄ = (K + σ_n² I)α − K α = σ_n² α: the residual shrinks as σ_n².
        const double error = (p.mean - y).cwiseAbs().maxCoeff();
        EXPECT_LT(error, 100 * sigma_n * sigma_n);
        EXPECT_LT(error, 0.02 * previous_error);
        previous_error = error;
        for (int i = 0; i < 8; i++) {
            // Observing y_i alone leaves σ_f²σ_n²/(σ_f²+σ_n²) < σ_n²; more data only lowers it.
            EXPECT_LE(p.variance[i], sigma_n * sigma_n + 1e-15) << "sigma_n=" << sigma_n;
            EXPECT_GT(p.variance[i], 0.1 * sigma_n * sigma_n) << "sigma_n=" << sigma_n;
        }
    }
    EXPECT_LT(previous_error, 1e-6);
}

TEST(GaussianProcessRegression, FarFromDataRevertsToPrior)
{
    const THyper h{0.5, 2.0, 0.3};
    GaussianProcessRegression gp(h);
    // No data: the prior.
    const auto prior = gp.predict(Eigen::MatrixXd::Zero(2, 3), true);
    EXPECT_DOUBLE_EQ(prior.mean[1], 0.0);
    EXPECT_DOUBLE_EQ(prior.variance[1], 4.0 + 0.09);
    EXPECT_DOUBLE_EQ(gp.logMarginalLikelihood(), 0.0);

    const Eigen::MatrixXd X = uniformPoints(20, 3, -1.0, 1.0, 2);
    gp.fit(X, sampleGp(X, h, 3));
    Eigen::MatrixXd far(1, 3);
    far << 40.0, -40.0, 40.0;  // > 100ℓ away: k* underflows to 0
    const auto p = gp.predict(far);
    EXPECT_DOUBLE_EQ(p.mean[0], 0.0);
    EXPECT_DOUBLE_EQ(p.variance[0], 4.0);
    EXPECT_DOUBLE_EQ(gp.predict(far, true).variance[0], 4.09);
}

TEST(GaussianProcessRegression, LogMarginalLikelihoodEqualsDirectEvaluation)
{
    for (const THyper h : {THyper{0.7, 1.0, 0.1}, THyper{2.0, 0.5, 0.4}, THyper{0.3, 3.0, 1.0}}) {
        const Eigen::MatrixXd X = uniformPoints(12, 3, -2.0, 2.0, 4);
        const Eigen::VectorXd y = sampleGp(X, THyper{1.0, 1.0, 0.2}, 5);
        GaussianProcessRegression gp(h);
        gp.fit(X, y);
        Eigen::MatrixXd K = seKernel(X, X, h);
        K.diagonal().array() += h.noise_std * h.noise_std;
        // −½ yᵀK⁻¹y − ½ log|K| − (n/2) log 2π with a full inverse and determinant (Eq. 2.30).
        const double direct = -0.5 * y.dot(K.inverse() * y) - 0.5 * std::log(K.determinant()) -
                              6.0 * std::log(2 * M_PI);
        EXPECT_NEAR(gp.logMarginalLikelihood(), direct, 1e-9 * std::abs(direct));
    }
}

TEST(GaussianProcessRegression, GradientMatchesCentralDifferences)
{
    const Eigen::MatrixXd X = uniformPoints(30, 2, 0.0, 3.0, 6);
    const Eigen::VectorXd y = sampleGp(X, THyper{0.8, 1.0, 0.1}, 7);
    for (const THyper h : {THyper{0.8, 1.0, 0.1}, THyper{0.3, 2.0, 0.5}, THyper{2.5, 0.4, 0.05}}) {
        GaussianProcessRegression gp(h);
        gp.fit(X, y);
        const Eigen::Vector3d g = gp.logMarginalLikelihoodGradient();
        const double step = 1e-5;
        for (int j = 0; j < 3; j++) {
            const auto at = [&](double delta) {
                Eigen::Vector3d t(std::log(h.length_scale), std::log(h.signal_std),
                                  std::log(h.noise_std));
                t[j] += delta;
                GaussianProcessRegression shifted(
                    THyper{std::exp(t[0]), std::exp(t[1]), std::exp(t[2])});
                shifted.fit(X, y);
                return shifted.logMarginalLikelihood();
            };
            const double fd = (at(step) - at(-step)) / (2 * step);
            EXPECT_NEAR(g[j], fd, 1e-5 * std::max(1.0, std::abs(fd))) << "j=" << j;
        }
    }
}

TEST(GaussianProcessRegression, OptimizationRecoversLengthScale)
{
    const THyper truth{0.6, 1.0, 0.1};
    const Eigen::MatrixXd X = uniformPoints(200, 2, 0.0, 4.0, 8);
    const Eigen::VectorXd y = sampleGp(X, truth, 9);
    GaussianProcessRegression gp;  // starts from ℓ = 1, σ_f = 1, σ_n = 0.1
    gp.fit(X, y);
    const auto result = gp.optimizeHyperParameters();
    EXPECT_NEAR(result.hyper.length_scale, truth.length_scale, 0.25 * truth.length_scale);
    EXPECT_NEAR(result.hyper.noise_std, truth.noise_std, 0.25 * truth.noise_std);
    EXPECT_NEAR(result.hyper.signal_std, truth.signal_std, 0.5 * truth.signal_std);
    EXPECT_DOUBLE_EQ(gp.hyperParameters().length_scale, result.hyper.length_scale);
    EXPECT_NEAR(gp.logMarginalLikelihood(), result.log_marginal_likelihood, 1e-9);
    // A stationary point: the gradient vanishes, and the evidence beats the true θ.
    EXPECT_LT(gp.logMarginalLikelihoodGradient().cwiseAbs().maxCoeff(), 1e-3);
    GaussianProcessRegression at_truth(truth);
    at_truth.fit(X, y);
    EXPECT_GE(result.log_marginal_likelihood, at_truth.logMarginalLikelihood());
}

TEST(GaussianProcessRegression, OptimizationHonoursBoundsAndFixedNoise)
{
    const Eigen::MatrixXd X = uniformPoints(60, 2, 0.0, 4.0, 10);
    const Eigen::VectorXd y = sampleGp(X, THyper{0.6, 1.0, 0.1}, 11);
    GaussianProcessRegression gp(THyper{1.0, 1.0, 0.3});
    gp.fit(X, y);
    GaussianProcessRegression::TOptimizationOptions options;
    options.optimize_noise = false;
    options.upper.length_scale = 0.4;  // below the best ℓ ≈ 0.6: the optimum sits on the bound
    const auto result = gp.optimizeHyperParameters(options);
    EXPECT_DOUBLE_EQ(result.hyper.noise_std, 0.3);
    EXPECT_NEAR(result.hyper.length_scale, 0.4, 1e-12);
    EXPECT_GT(gp.logMarginalLikelihoodGradient()[0], 0.0);  // would grow ℓ if it could
}

TEST(GaussianProcessRegression, EntropyMatchesDirectEvaluation)
{
    const THyper h{0.7, 1.2, 0.15};
    const Eigen::MatrixXd X = uniformPoints(25, 2, 0.0, 3.0, 12);
    GaussianProcessRegression gp(h);
    gp.fit(X, sampleGp(X, h, 13));
    const Eigen::MatrixXd Q = uniformPoints(5, 2, -0.5, 3.5, 14);

    // Σ = K** − K*ᵀ (K + σ_n² I)⁻¹ K* with a full inverse; H = ½ log det(2πe Σ).
    Eigen::MatrixXd K = seKernel(X, X, h);
    K.diagonal().array() += h.noise_std * h.noise_std;
    const Eigen::MatrixXd Ks = seKernel(X, Q, h);
    const Eigen::MatrixXd S = seKernel(Q, Q, h) - Ks.transpose() * K.inverse() * Ks;
    EXPECT_NEAR(gp.jointEntropy(Q), 0.5 * (5 * kLog2PiE + std::log(S.determinant())), 1e-8);
    Eigen::MatrixXd Sn = S;
    Sn.diagonal().array() += h.noise_std * h.noise_std;
    EXPECT_NEAR(gp.jointEntropy(Q, true), 0.5 * (5 * kLog2PiE + std::log(Sn.determinant())), 1e-8);
    EXPECT_LT((gp.predictiveCovariance(Q) - S).cwiseAbs().maxCoeff(), 1e-10);
    for (int i = 0; i < 5; i++) {
        EXPECT_NEAR(gp.entropy(Q.row(i).transpose()), 0.5 * (kLog2PiE + std::log(S(i, i))), 1e-8);
        EXPECT_NEAR(gp.jointEntropy(Q.row(i)), gp.entropy(Q.row(i).transpose()), 1e-12);
    }
    // Points far apart are independent: joint entropy = sum of the single ones = log(2πe σ_f²).
    Eigen::MatrixXd far(2, 2);
    far << 100.0, 0.0, -100.0, 0.0;
    EXPECT_NEAR(gp.jointEntropy(far), kLog2PiE + std::log(1.44), 1e-12);
    // A repeated point has a singular latent joint covariance, unless noise is added.
    Eigen::MatrixXd twice(2, 2);
    twice << 100.0, 0.0, 100.0, 0.0;
    EXPECT_EQ(gp.jointEntropy(twice), -std::numeric_limits<double>::infinity());
    EXPECT_TRUE(std::isfinite(gp.jointEntropy(twice, true)));
    EXPECT_DOUBLE_EQ(gp.jointEntropy(Eigen::MatrixXd(0, 2)), 0.0);
}

TEST(GaussianProcessRegression, RejectsBadInput)
{
    EXPECT_THROW(GaussianProcessRegression(THyper{0.0, 1.0, 0.1}), std::invalid_argument);
    EXPECT_THROW(GaussianProcessRegression(THyper{1.0, std::nan(""), 0.1}), std::invalid_argument);
    GaussianProcessRegression gp;
    EXPECT_THROW(gp.optimizeHyperParameters(), std::logic_error);
    EXPECT_THROW(gp.fit(Eigen::MatrixXd(3, 2), Eigen::VectorXd(2)), std::invalid_argument);
    EXPECT_THROW(gp.fit(Eigen::MatrixXd(0, 2), Eigen::VectorXd(0)), std::invalid_argument);
    Eigen::MatrixXd X = Eigen::MatrixXd::Zero(2, 2);
    X(1, 0) = std::numeric_limits<double>::infinity();
    EXPECT_THROW(gp.fit(X, Eigen::VectorXd::Zero(2)), std::invalid_argument);
    gp.fit(Eigen::MatrixXd::Zero(2, 2), Eigen::VectorXd::Ones(2));
    EXPECT_THROW(gp.predict(Eigen::MatrixXd::Zero(1, 3)), std::invalid_argument);
    EXPECT_THROW(gp.setHyperParameters(THyper{1.0, 1.0, -0.1}), std::invalid_argument);

    // Repeated inputs without noise: K + σ_n² I is singular; the previous fit is kept.
    GaussianProcessRegression exact(THyper{1.0, 1.0, 1e-12});
    Eigen::MatrixXd one(1, 2);
    one << 0.5, 0.5;
    exact.fit(one, Eigen::VectorXd::Constant(1, 2.0));
    EXPECT_THROW(exact.fit(Eigen::MatrixXd::Zero(2, 2), Eigen::VectorXd::Ones(2)),
                 std::runtime_error);
    EXPECT_EQ(exact.size(), 1u);
    EXPECT_NEAR(exact.predict(one).mean[0], 2.0, 1e-12);
    GaussianProcessRegression noisy(THyper{1.0, 1.0, 0.1});
    noisy.fit(Eigen::MatrixXd::Zero(2, 2), Eigen::VectorXd::Ones(2));
    EXPECT_THROW(noisy.setHyperParameters(THyper{1.0, 1.0, 1e-12}), std::runtime_error);
    EXPECT_DOUBLE_EQ(noisy.hyperParameters().noise_std, 0.1);
    EXPECT_EQ(noisy.size(), 2u);
}
