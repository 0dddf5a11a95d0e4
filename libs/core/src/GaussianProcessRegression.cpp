#include <mrpt_vslam/core/GaussianProcessRegression.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mrpt_vslam::core {
namespace {

using THyper = GaussianProcessRegression::THyperParameters;
constexpr double kLog2Pi = 1.8378770664093453;  // log(2π)
constexpr double kInf = std::numeric_limits<double>::infinity();

void checkHyper(const THyper& h)
{
    for (const double v : {h.length_scale, h.signal_std, h.noise_std}) {
        if (!std::isfinite(v) || !(v > 0)) {
            throw std::invalid_argument(
                "GaussianProcessRegression: hyperparameters must be finite and positive (ell=" +
                std::to_string(h.length_scale) + ", sigma_f=" + std::to_string(h.signal_std) +
                ", sigma_n=" + std::to_string(h.noise_std) + ")");
        }
    }
}

Eigen::Vector3d toLog(const THyper& h)
{
    return {std::log(h.length_scale), std::log(h.signal_std), std::log(h.noise_std)};
}

THyper fromLog(const Eigen::Vector3d& t)
{
    return {std::exp(t[0]), std::exp(t[1]), std::exp(t[2])};
}

/// Squared distances |X_i − X_j|², n × n.
Eigen::MatrixXd squaredDistances(const Eigen::MatrixXd& X)
{
    const Eigen::Index n = X.rows();
    Eigen::MatrixXd d2(n, n);
    for (Eigen::Index j = 0; j < n; j++) {
        d2(j, j) = 0;
        for (Eigen::Index i = j + 1; i < n; i++) {
            d2(i, j) = d2(j, i) = (X.row(i) - X.row(j)).squaredNorm();
        }
    }
    return d2;
}

/// log p(y|X, θ) and its gradient w.r.t. θ = (log ℓ, log σ_f, log σ_n); −∞ when K + σ_n² I is
/// not numerically positive definite.
struct TEvidence {
    double value = -kInf;
    Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
};

TEvidence evidence(const Eigen::MatrixXd& d2, const Eigen::VectorXd& y, const Eigen::Vector3d& t,
                   bool with_gradient)
{
    const THyper h = fromLog(t);
    const auto n = static_cast<double>(y.size());
    // K_f = σ_f² exp(−r² / (2ℓ²))   (Eq. 2.31)
    const Eigen::MatrixXd Kf =
        h.signal_std * h.signal_std *
        (d2.array() * (-0.5 / (h.length_scale * h.length_scale))).exp().matrix();
    Eigen::MatrixXd K = Kf;
    K.diagonal().array() += h.noise_std * h.noise_std;
    const Eigen::LLT<Eigen::MatrixXd> llt(K);
    TEvidence out;
    if (llt.info() != Eigen::Success) return out;
    const Eigen::VectorXd alpha = llt.solve(y);
    const double log_det_half = llt.matrixLLT().diagonal().array().log().sum();
    // log p(y|X) = −½ yᵀα − Σ log L_ii − (n/2) log 2π   (Alg. 2.1, line 7)
    out.value = -0.5 * y.dot(alpha) - log_det_half - 0.5 * n * kLog2Pi;
    if (!std::isfinite(out.value)) {
        out.value = -kInf;
        return out;
    }
    if (!with_gradient) return out;
    // ∂/∂θ_j = ½ tr(W ∂K/∂θ_j), W = ααᵀ − K⁻¹   (Eq. 5.9); tr(W A) = Σ W∘A for symmetric A.
    Eigen::MatrixXd W = -llt.solve(Eigen::MatrixXd::Identity(y.size(), y.size()));
    W.noalias() += alpha * alpha.transpose();
    // ∂K/∂log ℓ = K_f ∘ r²/ℓ²,  ∂K/∂log σ_f = 2K_f,  ∂K/∂log σ_n = 2σ_n² I
    const Eigen::ArrayXXd WKf = W.array() * Kf.array();
    out.gradient[0] = 0.5 * (WKf * d2.array()).sum() / (h.length_scale * h.length_scale);
    out.gradient[1] = WKf.sum();
    out.gradient[2] = h.noise_std * h.noise_std * W.trace();
    return out;
}

/// Median distance between inputs (deterministic subsample of at most 400 points), or 1 if 0.
double medianDistance(const Eigen::MatrixXd& X)
{
    const Eigen::Index n = X.rows();
    const Eigen::Index stride = std::max<Eigen::Index>(1, n / 400);
    std::vector<double> d;
    for (Eigen::Index i = 0; i < n; i += stride) {
        for (Eigen::Index j = i + stride; j < n; j += stride)
            d.push_back((X.row(i) - X.row(j)).norm());
    }
    if (d.empty()) return 1.0;
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    const double med = d[d.size() / 2];
    return med > 0 ? med : 1.0;
}

/// Log-bounds: a field at 0 takes the data-driven default.
void resolveBounds(const GaussianProcessRegression::TOptimizationOptions& o, double dist,
                   double rms, Eigen::Vector3d& lo, Eigen::Vector3d& hi)
{
    const auto pick = [](double given, double automatic) {
        return std::log(given > 0 ? given : automatic);
    };
    lo = {pick(o.lower.length_scale, 1e-3 * dist), pick(o.lower.signal_std, 1e-3 * rms),
          pick(o.lower.noise_std, 1e-4 * rms)};
    hi = {pick(o.upper.length_scale, 1e3 * dist), pick(o.upper.signal_std, 1e3 * rms),
          pick(o.upper.noise_std, 10 * rms)};
    for (int i = 0; i < 3; i++) {
        if (!(lo[i] <= hi[i]) || !std::isfinite(lo[i]) || !std::isfinite(hi[i])) {
            throw std::invalid_argument(
                "GaussianProcessRegression: bad hyperparameter bounds (lower > upper or "
                "negative)");
        }
    }
}

/// Cross-covariance k(A_i, B_j), |A| × |B|   (Eq. 2.31).
Eigen::MatrixXd kernelMatrix(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const THyper& h)
{
    if (A.cols() != B.cols() && A.rows() > 0 && B.rows() > 0) {
        throw std::invalid_argument("GaussianProcessRegression: query points have " +
                                    std::to_string(A.cols()) + " dimensions, training inputs " +
                                    std::to_string(B.cols()));
    }
    const double sf2 = h.signal_std * h.signal_std;
    const double inv_2ell2 = 0.5 / (h.length_scale * h.length_scale);
    // Points as contiguous columns.
    const Eigen::MatrixXd At = A.transpose(), Bt = B.transpose();
    Eigen::MatrixXd K(A.rows(), B.rows());
    for (Eigen::Index j = 0; j < B.rows(); j++) {
        for (Eigen::Index i = 0; i < A.rows(); i++) {
            K(i, j) = sf2 * std::exp(-(At.col(i) - Bt.col(j)).squaredNorm() * inv_2ell2);
        }
    }
    return K;
}

struct TAscent {
    Eigen::Vector3d theta;
    TEvidence best;
    int iterations = 0;
    int evaluations = 0;
};

/** Projected BFGS ascent of log p(y|X, θ) inside [lo, hi] (Nocedal & Wright 2006, Alg. 6.1,
 *  with Armijo backtracking and the gradient of active bounds zeroed). `free[i]` false keeps
 *  θ_i fixed. */
TAscent ascend(const Eigen::MatrixXd& d2, const Eigen::VectorXd& y, Eigen::Vector3d theta,
               const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
               const std::array<bool, 3>& free,
               const GaussianProcessRegression::TOptimizationOptions& o)
{
    constexpr double kArmijo = 1e-4;
    constexpr double kMaxStep = 3.0;  // [log units] per iteration
    TAscent a;
    a.theta = theta.cwiseMax(lo).cwiseMin(hi);
    a.best = evidence(d2, y, a.theta, true);
    a.evaluations = 1;
    if (!std::isfinite(a.best.value)) return a;
    Eigen::Matrix3d H = Eigen::Matrix3d::Identity();  // inverse Hessian of −log p
    for (; a.iterations < o.max_iterations; a.iterations++) {
        // Ascent direction g; components pushing against an active bound (or fixed) are dropped.
        Eigen::Vector3d g = a.best.gradient;
        for (int i = 0; i < 3; i++) {
            if (!free[i] || (a.theta[i] <= lo[i] && g[i] < 0) || (a.theta[i] >= hi[i] && g[i] > 0))
                g[i] = 0;
        }
        if (g.cwiseAbs().maxCoeff() < o.gradient_tolerance) break;
        Eigen::Vector3d dir = H * g;
        for (int i = 0; i < 3; i++) {
            if (g[i] == 0) dir[i] = 0;
        }
        if (!(dir.dot(g) > 0)) {
            H.setIdentity();
            dir = g;
        }
        const double longest = dir.cwiseAbs().maxCoeff();
        if (longest > kMaxStep) dir *= kMaxStep / longest;
        // Armijo backtracking on the projected path.
        bool accepted = false;
        TEvidence next;
        Eigen::Vector3d step;
        for (double t = 1.0; t > 1e-10; t *= 0.5) {
            step = (a.theta + t * dir).cwiseMax(lo).cwiseMin(hi) - a.theta;
            next = evidence(d2, y, a.theta + step, true);
            a.evaluations++;
            if (next.value >= a.best.value + kArmijo * g.dot(step)) {
                accepted = true;
                break;
            }
        }
        if (!accepted) break;
        const double gain = next.value - a.best.value;
        // BFGS update of the inverse Hessian of −log p: s = step, q = −(∇_new − ∇_old).
        const Eigen::Vector3d q = a.best.gradient - next.gradient;
        const double sq = step.dot(q);
        if (sq > 1e-12) {
            const double rho = 1.0 / sq;
            const Eigen::Matrix3d V = Eigen::Matrix3d::Identity() - rho * q * step.transpose();
            H = V.transpose() * H * V + rho * step * step.transpose();
        }
        a.theta += step;
        a.best = next;
        if (gain <= 1e-12 * (1.0 + std::abs(a.best.value))) break;
    }
    return a;
}

}  // namespace

GaussianProcessRegression::GaussianProcessRegression(const THyperParameters& hyper)
{
    checkHyper(hyper);
    m_hyper = hyper;
}

void GaussianProcessRegression::fit(const Eigen::MatrixXd& X, const Eigen::VectorXd& y)
{
    if (X.rows() == 0 || X.cols() == 0 || X.rows() != y.size()) {
        throw std::invalid_argument("GaussianProcessRegression::fit: need n ≥ 1 rows of X (got " +
                                    std::to_string(X.rows()) + " × " + std::to_string(X.cols()) +
                                    ") and as many targets (got " + std::to_string(y.size()) + ")");
    }
    if (!X.allFinite() || !y.allFinite()) {
        throw std::invalid_argument("GaussianProcessRegression::fit: non-finite data");
    }
    factorise(X, y, m_hyper);
}

void GaussianProcessRegression::setHyperParameters(const THyperParameters& hyper)
{
    checkHyper(hyper);
    if (size() > 0) {
        factorise(m_X, m_y, hyper);
    } else {
        m_hyper = hyper;
    }
}

void GaussianProcessRegression::factorise(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                                          const THyperParameters& hyper)
{
    Eigen::MatrixXd K = kernelMatrix(X, X, hyper);
    K.diagonal().array() += hyper.noise_std * hyper.noise_std;
    // L = cholesky(K + σ_n² I), α = Lᵀ \ (L \ y)   (Alg. 2.1, lines 2–3)
    Eigen::LLT<Eigen::MatrixXd> llt(K);
    if (llt.info() != Eigen::Success) {
        throw std::runtime_error(
            "GaussianProcessRegression: K + sigma_n^2 I is not positive definite (repeated "
            "inputs with a tiny noise_std?)");
    }
    // Commit only after success: a failure leaves the previous state untouched.
    m_alpha = llt.solve(y);
    m_llt = std::move(llt);
    m_X = X;
    m_y = y;
    m_hyper = hyper;
}

GaussianProcessRegression::TOptimizationResult GaussianProcessRegression::optimizeHyperParameters(
    const TOptimizationOptions& options)
{
    if (size() == 0) {
        throw std::logic_error(
            "GaussianProcessRegression::optimizeHyperParameters: call fit() "
            "first");
    }
    const double dist = medianDistance(m_X);
    const double rms_raw = std::sqrt(m_y.squaredNorm() / static_cast<double>(m_y.size()));
    const double rms = rms_raw > 0 ? rms_raw : 1.0;
    Eigen::Vector3d lo, hi;
    resolveBounds(options, dist, rms, lo, hi);
    const std::array<bool, 3> free{true, true, options.optimize_noise};
    if (!options.optimize_noise) lo[2] = hi[2] = std::log(m_hyper.noise_std);

    // Starting points: the current θ, then ℓ = d·3^{0, −1, 1, −2, 2, …}.
    std::vector<Eigen::Vector3d> starts{toLog(m_hyper)};
    for (int k = 0; k < options.restarts; k++) {
        const double factor = std::pow(k % 2 == 1 ? 1.0 / 3.0 : 3.0, (k + 1) / 2);
        starts.emplace_back(
            std::log(dist * factor), std::log(rms),
            options.optimize_noise ? std::log(0.1 * rms) : std::log(m_hyper.noise_std));
    }
    const Eigen::MatrixXd d2 = squaredDistances(m_X);
    TOptimizationResult result;
    result.log_marginal_likelihood = -kInf;
    Eigen::Vector3d best_theta = toLog(m_hyper);
    for (const auto& start : starts) {
        const TAscent a = ascend(d2, m_y, start, lo, hi, free, options);
        result.iterations += a.iterations;
        result.evaluations += a.evaluations;
        if (a.best.value > result.log_marginal_likelihood) {
            result.log_marginal_likelihood = a.best.value;
            best_theta = a.theta;
        }
    }
    if (!std::isfinite(result.log_marginal_likelihood)) {
        throw std::runtime_error(
            "GaussianProcessRegression::optimizeHyperParameters: no "
            "starting point gave a positive-definite covariance");
    }
    setHyperParameters(fromLog(best_theta));
    result.hyper = m_hyper;
    return result;
}

GaussianProcessRegression::TOptimizationResult GaussianProcessRegression::optimizeHyperParameters()
{
    return optimizeHyperParameters(TOptimizationOptions());
}

double GaussianProcessRegression::kernel(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const
{
    // k(x, x') = σ_f² exp(−|x − x'|² / (2ℓ²))   (Eq. 2.31)
    const double ell2 = m_hyper.length_scale * m_hyper.length_scale;
    return m_hyper.signal_std * m_hyper.signal_std * std::exp(-0.5 * (a - b).squaredNorm() / ell2);
}

GaussianProcessRegression::TPrediction GaussianProcessRegression::predict(
    const Eigen::MatrixXd& X_query, bool include_noise) const
{
    const double sf2 = m_hyper.signal_std * m_hyper.signal_std;
    const double extra = include_noise ? m_hyper.noise_std * m_hyper.noise_std : 0.0;
    TPrediction p;
    if (size() == 0) {
        p.mean = Eigen::VectorXd::Zero(X_query.rows());
        p.variance = Eigen::VectorXd::Constant(X_query.rows(), sf2 + extra);
        return p;
    }
    const Eigen::MatrixXd Ks = kernelMatrix(m_X, X_query, m_hyper);  // n × m
    // f̄* = k*ᵀ α;  v = L \ k*;  V[f*] = k(x*, x*) − vᵀv   (Alg. 2.1, lines 4–6)
    p.mean = Ks.transpose() * m_alpha;
    const Eigen::MatrixXd V = m_llt.matrixL().solve(Ks);
    p.variance = (sf2 - V.colwise().squaredNorm().transpose().array()).max(0.0) + extra;
    return p;
}

Eigen::MatrixXd GaussianProcessRegression::predictiveCovariance(const Eigen::MatrixXd& X_query,
                                                                bool include_noise) const
{
    Eigen::MatrixXd S = kernelMatrix(X_query, X_query, m_hyper);
    if (size() > 0) {
        const Eigen::MatrixXd V = m_llt.matrixL().solve(kernelMatrix(m_X, X_query, m_hyper));
        // cov(f*) = K** − K*ᵀ (K + σ_n² I)⁻¹ K* = K** − VᵀV   (Eq. 2.24)
        S.noalias() -= V.transpose() * V;
    }
    if (include_noise) S.diagonal().array() += m_hyper.noise_std * m_hyper.noise_std;
    return S;
}

double GaussianProcessRegression::logMarginalLikelihood() const
{
    if (size() == 0) return 0.0;
    const auto n = static_cast<double>(size());
    // log p(y|X) = −½ yᵀα − Σ log L_ii − (n/2) log 2π   (Alg. 2.1, line 7)
    return -0.5 * m_y.dot(m_alpha) - m_llt.matrixLLT().diagonal().array().log().sum() -
           0.5 * n * kLog2Pi;
}

Eigen::Vector3d GaussianProcessRegression::logMarginalLikelihoodGradient() const
{
    if (size() == 0) return Eigen::Vector3d::Zero();
    return evidence(squaredDistances(m_X), m_y, toLog(m_hyper), true).gradient;
}

double GaussianProcessRegression::entropy(const Eigen::VectorXd& x, bool include_noise) const
{
    const double var = predict(x.transpose(), include_noise).variance[0];
    // H = ½ log(2πe σ²)   (App. A.5)
    return var > 0 ? 0.5 * (kLog2Pi + 1.0 + std::log(var)) : -kInf;
}

double GaussianProcessRegression::jointEntropy(const Eigen::MatrixXd& X_query,
                                               bool include_noise) const
{
    if (X_query.rows() == 0) return 0.0;
    const Eigen::LLT<Eigen::MatrixXd> llt(predictiveCovariance(X_query, include_noise));
    const auto m = static_cast<double>(X_query.rows());
    if (llt.info() != Eigen::Success || !(llt.matrixLLT().diagonal().minCoeff() > 0)) return -kInf;
    // H = ½ log det(2πe Σ) = ½ m (log 2π + 1) + Σ log L_ii   (App. A.5)
    return 0.5 * m * (kLog2Pi + 1.0) + llt.matrixLLT().diagonal().array().log().sum();
}

}  // namespace mrpt_vslam::core
