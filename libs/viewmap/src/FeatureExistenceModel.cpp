#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/viewmap/FeatureExistenceModel.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace mrpt_vslam::viewmap {

using core::requireOption;

void FeatureExistenceModel::TOptions::validate() const
{
    requireOption(max_points >= 3, "max_points", "must be >= 3");
    requireOption(refit_every >= 1, "refit_every", "must be >= 1");
    requireOption(confidence_sigmas >= 0 && std::isfinite(confidence_sigmas), "confidence_sigmas",
                  "must be finite and >= 0");
}

void FeatureExistenceModel::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                         const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(max_points, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(refit_every, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(confidence_sigmas, double, cfg, section);
    try {
        validate();
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("[" + section + "] " + e.what());
    }
}

void FeatureExistenceModel::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                                       const std::string& section) const
{
    MRPT_SAVE_CONFIG_VAR(max_points, cfg, section);
    MRPT_SAVE_CONFIG_VAR(refit_every, cfg, section);
    MRPT_SAVE_CONFIG_VAR(confidence_sigmas, cfg, section);
}

FeatureExistenceModel::FeatureExistenceModel() : FeatureExistenceModel(TOptions()) {}

FeatureExistenceModel::FeatureExistenceModel(const TOptions& options)
    : m_options(options), m_gp(core::GaussianProcessRegression::THyperParameters{0.5, 0.3, 0.3})
{
    m_options.validate();
}

FeatureExistenceModel::TContent FeatureExistenceModel::fit(const Eigen::Matrix3Xd& rays,
                                                           const std::vector<bool>& consistent,
                                                           mrpt::random::CRandomGenerator& rng)
{
    const size_t n = size_t(rays.cols());
    if (consistent.size() != n)
        throw std::invalid_argument("FeatureExistenceModel::fit: " + std::to_string(n) +
                                    " rays but " + std::to_string(consistent.size()) + " targets");
    TContent content;
    if (n < 3) return content;
    std::vector<size_t> used(n);
    std::iota(used.begin(), used.end(), 0);
    const size_t m = std::min(n, size_t(m_options.max_points));
    if (m < n) {
        // Partial Fisher-Yates with the step's generator: a seeded, reproducible subset.
        for (size_t i = 0; i < m; i++)
            std::swap(used[i], used[i + rng.drawUniform32bit() % (n - i)]);
        used.resize(m);
        std::sort(used.begin(), used.end());
    }
    Eigen::MatrixXd X(m, 3);
    Eigen::VectorXd y(m);
    for (size_t i = 0; i < m; i++) {
        X.row(Eigen::Index(i)) = rays.col(Eigen::Index(used[i])).transpose();
        y(Eigen::Index(i)) = consistent[used[i]] ? 1.0 : 0.0;
    }
    content.prior_mean = y.mean();
    content.points = m;
    y.array() -= content.prior_mean;
    try {
        m_gp.fit(X, y);
        if (m_fits++ % m_options.refit_every == 0 && y.squaredNorm() > 0) {
            core::GaussianProcessRegression::TOptimizationOptions opt;
            opt.restarts = 0;  // warm start from the previous hyperparameters
            m_gp.optimizeHyperParameters(opt);
        }
    } catch (const std::runtime_error&) {
        // K + σ_n² I not positive definite (e.g. repeated rays): no information this step.
        return content;
    }
    content.hyper = m_gp.hyperParameters();
    const auto pred = m_gp.predict(X);
    const double kappa = m_options.confidence_sigmas;
    double sum = 0, sum_lower = 0;
    for (Eigen::Index k = 0; k < pred.mean.size(); k++) {
        const double p = content.prior_mean + pred.mean(k);
        sum += std::clamp(p, 0.0, 1.0);
        sum_lower += std::clamp(p - kappa * std::sqrt(pred.variance(k)), 0.0, 1.0);
    }
    content.existence = sum / double(m);
    content.lower_existence = sum_lower / double(m);
    content.sure_points = content.lower_existence * double(n);
    return content;
}

}  // namespace mrpt_vslam::viewmap
