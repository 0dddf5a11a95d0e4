#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/math/distributions.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/core/KLDSampling.h>
#include <mrpt_vslam/core/OptionChecks.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <stdexcept>

namespace mrpt_vslam::core {

void TKLDParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                    const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(KLD_minSampleSize, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(KLD_maxSampleSize, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(KLD_binSize_XY, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR_DEGREES(KLD_binSize_PHI, cfg, section);
    MRPT_LOAD_CONFIG_VAR(KLD_delta, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(KLD_epsilon, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(KLD_minSamplesPerBin, double, cfg, section);
}

void TKLDParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                  const std::string& section) const
{
    MRPT_SAVE_CONFIG_VAR(KLD_minSampleSize, cfg, section);
    MRPT_SAVE_CONFIG_VAR(KLD_maxSampleSize, cfg, section);
    MRPT_SAVE_CONFIG_VAR(KLD_binSize_XY, cfg, section);
    MRPT_SAVE_CONFIG_VAR_DEGREES(KLD_binSize_PHI, cfg, section);
    MRPT_SAVE_CONFIG_VAR(KLD_delta, cfg, section);
    MRPT_SAVE_CONFIG_VAR(KLD_epsilon, cfg, section);
    MRPT_SAVE_CONFIG_VAR(KLD_minSamplesPerBin, cfg, section);
}

void validateKLDParams(const TKLDParams& p)
{
    requireOption(p.KLD_binSize_XY > 0 && std::isfinite(p.KLD_binSize_XY), "KLD_binSize_XY",
                  "must be finite and > 0");
    requireOption(p.KLD_binSize_PHI > 0 && std::isfinite(p.KLD_binSize_PHI), "KLD_binSize_PHI",
                  "must be finite and > 0");
    requireOption(p.KLD_epsilon > 0 && std::isfinite(p.KLD_epsilon), "KLD_epsilon",
                  "must be finite and > 0");
    requireOption(p.KLD_delta > 0 && p.KLD_delta < 1, "KLD_delta", "must be in (0, 1)");
    requireOption(p.KLD_minSampleSize >= 1, "KLD_minSampleSize", "must be >= 1");
    requireOption(p.KLD_maxSampleSize >= p.KLD_minSampleSize, "KLD_maxSampleSize",
                  "must be >= KLD_minSampleSize");
    requireOption(p.KLD_minSamplesPerBin >= 0 && std::isfinite(p.KLD_minSamplesPerBin),
                  "KLD_minSamplesPerBin", "must be finite and >= 0");
}

size_t kldSampleCount(size_t bins, const TKLDParams& p)
{
    double n = 0;
    if (bins > 1) {
        const double k1 = double(bins - 1);
        const double a = 2 / (9 * k1);
        const double z = mrpt::math::normalQuantile(1 - p.KLD_delta);
        n = std::ceil(k1 / (2 * p.KLD_epsilon) * std::pow(1 - a + std::sqrt(a) * z, 3));
    }
    n = std::max({n, double(p.KLD_minSampleSize), std::ceil(p.KLD_minSamplesPerBin * bins)});
    return size_t(std::min(n, double(p.KLD_maxSampleSize)));
}

std::vector<size_t> kldResample(const std::vector<double>& log_w,
                                const std::vector<mrpt::math::TPose2D>& poses, const TKLDParams& p,
                                mrpt::random::CRandomGenerator& rng)
{
    if (log_w.empty() || log_w.size() != poses.size())
        throw std::invalid_argument("kldResample: one pose per weight, at least one");
    validateKLDParams(p);
    // cumulative normalised weights
    const double max_log_w = *std::max_element(log_w.begin(), log_w.end());
    std::vector<double> cdf(log_w.size());
    double sum = 0;
    for (size_t i = 0; i < log_w.size(); i++) cdf[i] = sum += std::exp(log_w[i] - max_log_w);
    std::set<std::array<long long, 3>> bins;
    std::vector<size_t> drawn;
    for (size_t needed = kldSampleCount(0, p); drawn.size() < needed;) {
        const double u = rng.drawUniform(0.0, sum);
        const size_t i = std::min(size_t(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin()),
                                  cdf.size() - 1);
        drawn.push_back(i);
        const auto& x = poses[i];
        if (bins.insert({std::llround(std::floor(x.x / p.KLD_binSize_XY)),
                         std::llround(std::floor(x.y / p.KLD_binSize_XY)),
                         std::llround(std::floor(mrpt::math::wrapToPi(x.phi) / p.KLD_binSize_PHI))})
                .second)
            needed = kldSampleCount(bins.size(), p);
    }
    return drawn;
}

}  // namespace mrpt_vslam::core
