#include <mrpt/config/CConfigFileBase.h>
#include <mrpt_vslam/core/ConfigChoice.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/viewmap/ViewInitializationPolicy.h>

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::viewmap {

using core::requireOption;

const char* TViewDecision::reasonName(TReason r)
{
    switch (r) {
        case TReason::None:
            return "none";
        case TReason::FirstView:
            return "first_view";
        case TReason::NoObservation:
            return "no_observation";
        case TReason::FewInliers:
            return "few_inliers";
        case TReason::TooFar:
            return "too_far";
        case TReason::InformationDeficit:
            return "information_deficit";
        case TReason::LowExistence:
            return "low_existence";
    }
    return "?";
}

void ViewInitializationPolicy::TOptions::validate() const
{
    requireOption(min_view_spacing >= 0 && std::isfinite(min_view_spacing), "min_view_spacing",
                  "must be finite and >= 0");
    requireOption(min_inliers >= 1, "min_inliers", "must be >= 1");
    requireOption(max_view_distance > min_view_spacing && std::isfinite(max_view_distance),
                  "max_view_distance", "must be finite and > min_view_spacing");
    requireOption(information_deficit >= 0 && std::isfinite(information_deficit),
                  "information_deficit", "must be finite and >= 0");
    requireOption(deficit_frames >= 1, "deficit_frames", "must be >= 1");
    requireOption(trend_frames >= 1, "trend_frames", "must be >= 1");
    requireOption(min_sure_points >= 0 && std::isfinite(min_sure_points), "min_sure_points",
                  "must be finite and >= 0");
    existence.validate();
}

void ViewInitializationPolicy::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
    policy = core::readChoice(
        cfg, section, "policy",
        {{"traditional", TKind::Traditional}, {"information", TKind::Information}}, policy);
    MRPT_LOAD_CONFIG_VAR(min_view_spacing, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(min_inliers, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(max_view_distance, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(information_deficit, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(deficit_frames, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(min_sure_points, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(trend_frames, int, cfg, section);
    existence.loadFromConfigFile(cfg, section);
    try {
        validate();
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("[" + section + "] " + e.what());
    }
}

void ViewInitializationPolicy::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                                          const std::string& section) const
{
    cfg.write(section, "policy", policy == TKind::Traditional ? "traditional" : "information");
    MRPT_SAVE_CONFIG_VAR(min_view_spacing, cfg, section);
    MRPT_SAVE_CONFIG_VAR(min_inliers, cfg, section);
    MRPT_SAVE_CONFIG_VAR(max_view_distance, cfg, section);
    MRPT_SAVE_CONFIG_VAR(information_deficit, cfg, section);
    MRPT_SAVE_CONFIG_VAR(deficit_frames, cfg, section);
    MRPT_SAVE_CONFIG_VAR(min_sure_points, cfg, section);
    MRPT_SAVE_CONFIG_VAR(trend_frames, cfg, section);
    existence.saveToConfigFile(cfg, section);
}

std::unique_ptr<ViewInitializationPolicy> ViewInitializationPolicy::create(const TOptions& options)
{
    options.validate();
    if (options.policy == TKind::Traditional)
        return std::make_unique<TraditionalViewPolicy>(options);
    return std::make_unique<InformationViewPolicy>(options);
}

std::optional<TViewDecision> ViewInitializationPolicy::commonRules(
    const TViewPolicyInputs& in) const
{
    TViewDecision d;
    if (in.ekf->viewCount() == 0) {
        d.add = true;
        d.reason = TViewDecision::TReason::FirstView;
        return d;
    }
    if (in.nearest_view_distance < m_options.min_view_spacing) return d;  // too close to add
    return std::nullopt;
}

TViewDecision TraditionalViewPolicy::decide(const TViewPolicyInputs& in,
                                            mrpt::random::CRandomGenerator&)
{
    if (auto d = commonRules(in)) return *d;
    TViewDecision d;
    size_t best = 0;
    for (const auto& o : in.observed) best = std::max(best, o.inliers);
    using R = TViewDecision::TReason;
    if (in.observed.empty())
        d.reason = R::NoObservation;
    else if (best < size_t(m_options.min_inliers))
        d.reason = R::FewInliers;
    else if (in.nearest_view_distance > m_options.max_view_distance)
        d.reason = R::TooFar;
    d.add = d.reason != R::None;
    return d;
}

InformationViewPolicy::InformationViewPolicy(const TOptions& options)
    : ViewInitializationPolicy(options), m_existence(options.existence)
{
}

TViewDecision InformationViewPolicy::decide(const TViewPolicyInputs& in,
                                            mrpt::random::CRandomGenerator& rng)
{
    using R = TViewDecision::TReason;
    // Step 1: the existence model learns from every image, also the ones no rule looks at.
    const auto content = in.features ? m_existence.fit(in.features->rays, in.consistent, rng)
                                     : FeatureExistenceModel::TContent();
    const double n = content.sure_points;
    // Trend: the mean decline per frame over the last trend_frames frames since the last view.
    m_recent_sure_points.push_back(n);
    if (m_recent_sure_points.size() > size_t(m_options.trend_frames) + 1)
        m_recent_sure_points.pop_front();
    double n_next = n;
    if (const size_t k = m_recent_sure_points.size() - 1; k > 0)
        n_next -= std::max(0.0, (m_recent_sure_points.front() - n) / double(k));

    if (auto d = commonRules(in)) {
        d->sure_points = n;
        if (d->add) restart();
        return *d;
    }
    TViewDecision d;
    d.sure_points = n;
    if (in.observed.empty())
        d.reason = R::NoObservation;
    else if (n_next < m_options.min_sure_points)
        d.reason = R::LowExistence;
    else {
        // Steps 2-3: the observed views' hypothetical update after the next motion.
        std::vector<ViewMapEKF::THypotheticalObservation> next;
        for (const auto& o : in.observed) next.push_back({o.view, o.R * (n / n_next)});
        const Eigen::Matrix3d P_next =
            in.ekf->robotCovarianceAfterUpdates(next, in.P_vv_predicted - in.P_vv_previous);
        // Step 4: gain minus loss (the 2πe terms cancel), doc/view-slam.md §4.2.
        d.information_balance =
            0.5 * std::log(in.ekf->robotCovariance().determinant() / P_next.determinant());
        m_deficits = d.information_balance < -m_options.information_deficit ? m_deficits + 1 : 0;
        if (m_deficits >= m_options.deficit_frames) d.reason = R::InformationDeficit;
    }
    d.add = d.reason != R::None;
    if (d.add) restart();
    return d;
}

void InformationViewPolicy::restart()
{
    m_recent_sure_points.clear();
    m_deficits = 0;
}

}  // namespace mrpt_vslam::viewmap
