#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cstddef>

namespace mrpt_vslam::core {

/** Gaussian-process regression with a zero prior mean and the squared-exponential kernel
 *  (Rasmussen & Williams, "Gaussian Processes for Machine Learning", MIT Press 2006):
 *
 *      k(x, x') = σ_f² exp(−|x − x'|² / (2ℓ²)),   y = f(x) + ε,  ε ~ N(0, σ_n²)   (Eq. 2.31)
 *
 *  on inputs of any dimension (one row of X per sample). Steps (Alg. 2.1):
 *   1. L = cholesky(K + σ_n² I),  α = Lᵀ \ (L \ y)                         (fit())
 *   2. mean f̄* = k*ᵀ α;  v = L \ k*;  variance V[f*] = k(x*, x*) − vᵀv       (predict())
 *   3. log p(y|X) = −½ yᵀα − Σᵢ log Lᵢᵢ − (n/2) log 2π (logMarginalLikelihood()) Hyperparameters θ
 * = (log ℓ, log σ_f, log σ_n) are fitted by maximising step 3 (Sec. 5.4.1) with its gradient ∂/∂θⱼ
 * log p(y|X) = ½ tr((ααᵀ − K⁻¹) ∂K/∂θⱼ) (Eq. 5.9), by projected BFGS with an Armijo line search
 * inside box bounds, from several starting points (optimizeHyperParameters()).
 *
 *  Predictive variances are those of the latent f* by default; pass `include_noise = true` for
 *  the noisy target y* (adds σ_n²). Far from the data the latent variance tends to σ_f².
 *  The prior mean is zero: subtract a known or empirical mean from the targets first.
 *
 *  Information content (for deciding whether a new observation is informative): the
 *  differential entropy of the predictive Gaussian, H = ½ log(2πe σ²) at one point and
 *  H = ½ log det(2πe Σ) for the joint predictive at m points (App. A.5).
 *
 *  Usage:
 *   1. `GaussianProcessRegression gp(THyperParameters{ell, sigma_f, sigma_n});`
 *   2. `gp.fit(X, y);` and, optionally, `gp.optimizeHyperParameters();` (refits).
 *   3. `auto p = gp.predict(X_query);`, `gp.entropy(x)`, `gp.jointEntropy(X_query)`.
 *  With no data (before fit()) predictions are the prior: mean 0, variance σ_f².
 */
class GaussianProcessRegression {
  public:
    /// Kernel and noise hyperparameters; all must be finite and positive.
    struct THyperParameters {
        double length_scale = 1.0;  ///< ℓ [input units]
        double signal_std = 1.0;    ///< σ_f [target units]
        double noise_std = 0.1;     ///< σ_n [target units]
    };

    /// Options of optimizeHyperParameters().
    struct TOptimizationOptions {
        /// Extra starting points besides the current hyperparameters: ℓ = d·3^{0, −1, 1, −2, 2, …}
        /// (d: median distance between inputs), σ_f = RMS of y, σ_n = 0.1·RMS of y.
        int restarts = 3;
        int max_iterations = 100;          ///< BFGS iterations per starting point
        double gradient_tolerance = 1e-5;  ///< stop when |projected ∇ log p|_∞ is below
        bool optimize_noise = true;        ///< false: keep σ_n fixed
        /// Box bounds; a field left at 0 is set from the data: ℓ ∈ [10⁻³d, 10³d],
        /// σ_f ∈ [10⁻³, 10³]·RMS(y), σ_n ∈ [10⁻⁴, 10]·RMS(y).
        THyperParameters lower{0, 0, 0};
        THyperParameters upper{0, 0, 0};
    };

    /// Outcome of optimizeHyperParameters().
    struct TOptimizationResult {
        THyperParameters hyper;              ///< best hyperparameters found (now in use)
        double log_marginal_likelihood = 0;  ///< log p(y|X, θ) at them
        int iterations = 0;                  ///< BFGS iterations over all starting points
        int evaluations = 0;                 ///< likelihood evaluations over all starting points
    };

    /// Predictive means and variances at m query points.
    struct TPrediction {
        Eigen::VectorXd mean;      ///< [target units]
        Eigen::VectorXd variance;  ///< [target units²], clamped at 0
    };

    GaussianProcessRegression() = default;
    /// \throw std::invalid_argument for non-finite or non-positive hyperparameters.
    explicit GaussianProcessRegression(const THyperParameters& hyper);

    /// @name Training
    /// @{
    /** Stores the data and factorises K + σ_n² I (Alg. 2.1, lines 2–3).
     *  \param X n × d inputs, one sample per row; \param y n targets.
     *  \throw std::invalid_argument for empty, mismatched or non-finite data;
     *  std::runtime_error when K + σ_n² I is not numerically positive definite (the previous
     *  data and fit are then kept). */
    void fit(const Eigen::MatrixXd& X, const Eigen::VectorXd& y);

    /** Maximises log p(y|X, θ) over θ = (log ℓ, log σ_f, log σ_n) within the bounds and refits
     *  with the best θ. Deterministic. \throw std::logic_error before fit(). */
    TOptimizationResult optimizeHyperParameters(const TOptimizationOptions& options);
    /// optimizeHyperParameters() with the default TOptimizationOptions.
    TOptimizationResult optimizeHyperParameters();

    /// Sets the hyperparameters and refits the stored data, if any.
    void setHyperParameters(const THyperParameters& hyper);
    const THyperParameters& hyperParameters() const { return m_hyper; }
    /// Number of training samples.
    size_t size() const { return static_cast<size_t>(m_X.rows()); }
    /// @}

    /// @name Prediction
    /// @{
    /// k(a, b) with the current hyperparameters; a and b are points (same dimension).
    double kernel(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;

    /// Predictive mean and variance at each row of `X_query` (Alg. 2.1, lines 4–6).
    TPrediction predict(const Eigen::MatrixXd& X_query, bool include_noise = false) const;

    /// Joint predictive covariance K** − K*ᵀ(K + σ_n² I)⁻¹K* (Eq. 2.24), m × m.
    Eigen::MatrixXd predictiveCovariance(const Eigen::MatrixXd& X_query,
                                         bool include_noise = false) const;
    /// @}

    /// @name Model evidence
    /// @{
    /// log p(y|X, θ) of the stored data (Eq. 2.30; 0 with no data).
    double logMarginalLikelihood() const;
    /// ∂ log p(y|X, θ) / ∂(log ℓ, log σ_f, log σ_n) (Eq. 5.9).
    Eigen::Vector3d logMarginalLikelihoodGradient() const;
    /// @}

    /// @name Information content [nats]
    /// @{
    /// ½ log(2πe σ²) of the predictive at point x (−∞ for zero variance).
    double entropy(const Eigen::VectorXd& x, bool include_noise = false) const;
    /// ½ log det(2πe Σ) of the joint predictive at the rows of `X_query` (−∞ when Σ is
    /// numerically singular, e.g. repeated points without noise).
    double jointEntropy(const Eigen::MatrixXd& X_query, bool include_noise = false) const;
    /// @}

  private:
    /// Factorises K + σ_n² I of (X, y) with `hyper` and, on success only, stores all of them.
    void factorise(const Eigen::MatrixXd& X, const Eigen::VectorXd& y,
                   const THyperParameters& hyper);

    THyperParameters m_hyper;
    Eigen::MatrixXd m_X;                ///< n × d training inputs
    Eigen::VectorXd m_y;                ///< n training targets
    Eigen::LLT<Eigen::MatrixXd> m_llt;  ///< L Lᵀ = K + σ_n² I
    Eigen::VectorXd m_alpha;            ///< (K + σ_n² I)⁻¹ y
};

}  // namespace mrpt_vslam::core
