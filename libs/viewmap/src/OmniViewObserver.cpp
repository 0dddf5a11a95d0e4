#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/viewmap/OmniViewObserver.h>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace mrpt_vslam::viewmap {

using core::requireParameter;

namespace {

/// [rad] step of the central differences of the residuals.
constexpr double kDiffStep = 1e-6;
/// Gauss-Newton: at most this many steps, stopping once a step is below kConverged [rad].
constexpr int kMaxIterations = 5;
constexpr double kConverged = 1e-9;
/// det(JᵀJ) / trace(JᵀJ)² below which (φ, β) counts as unobservable from the matches.
constexpr double kMinDeterminant = 1e-12;
/// Rounds of inlier re-selection at 3 σ̂ after the refinement.
constexpr int kMaxReselections = 3;
/// Lower bound of 1 − leverage in the studentized residuals.
constexpr double kMinOneMinusLeverage = 1e-6;

/// Sampson residual on the sphere, with the sign of the epipolar constraint p_vᵀ E p_l.
double signedResidual(const PlanarEssentialMatrix& E, const Eigen::Vector3d& p_v,
                      const Eigen::Vector3d& p_l)
{
    return std::copysign(E.residual(p_v, p_l), p_v.dot(E.matrix() * p_l));
}

/// Signed residuals of the matches and their gradients J_k = ∂r_k/∂(φ, β) at z.
struct TLinearization {
    std::vector<double> r;
    std::vector<Eigen::Vector2d> J;
    Eigen::Matrix2d JtJ = Eigen::Matrix2d::Zero();
};

/// nullopt if a residual or a gradient is not finite.
std::optional<TLinearization> linearize(const TViewObservation& z, const Eigen::Matrix3Xd& rays_v,
                                        const Eigen::Matrix3Xd& rays_l,
                                        const std::vector<size_t>& indices)
{
    // Central differences in φ and β.
    const auto E = PlanarEssentialMatrix::fromMotion(z.phi, z.beta);
    const std::array<PlanarEssentialMatrix, 4> shifted{
        PlanarEssentialMatrix::fromMotion(z.phi + kDiffStep, z.beta),
        PlanarEssentialMatrix::fromMotion(z.phi - kDiffStep, z.beta),
        PlanarEssentialMatrix::fromMotion(z.phi, z.beta + kDiffStep),
        PlanarEssentialMatrix::fromMotion(z.phi, z.beta - kDiffStep)};
    TLinearization lin;
    lin.r.reserve(indices.size());
    lin.J.reserve(indices.size());
    for (size_t k : indices) {
        const Eigen::Vector3d p_v = rays_v.col(Eigen::Index(k));
        const Eigen::Vector3d p_l = rays_l.col(Eigen::Index(k));
        const double r = signedResidual(E, p_v, p_l);
        const Eigen::Vector2d J(
            (signedResidual(shifted[0], p_v, p_l) - signedResidual(shifted[1], p_v, p_l)) /
                (2 * kDiffStep),
            (signedResidual(shifted[2], p_v, p_l) - signedResidual(shifted[3], p_v, p_l)) /
                (2 * kDiffStep));
        if (!std::isfinite(r) || !J.allFinite()) return std::nullopt;
        lin.r.push_back(r);
        lin.J.push_back(J);
        lin.JtJ += J * J.transpose();
    }
    return lin;
}

bool isRegular(const Eigen::Matrix2d& JtJ)
{
    return JtJ.determinant() > kMinDeterminant * JtJ.trace() * JtJ.trace();
}

/** The matches of `indices` whose studentized residual t_k = r_k / √(1 − h_k) for z is at most
 *  3 σ̂, with h_k = J_kᵀ (JᵀJ)⁻¹ J_k the leverage and σ̂ = 1.4826 median |t| (robust; residuals
 *  are centred on 0). The leverage matters: a wrong match far from the others in (φ, β)
 *  sensitivity pulls the fit towards itself and leaves a small raw residual. */
std::vector<size_t> studentizedInliers(const TViewObservation& z, const Eigen::Matrix3Xd& rays_v,
                                       const Eigen::Matrix3Xd& rays_l,
                                       const std::vector<size_t>& indices)
{
    const auto lin = linearize(z, rays_v, rays_l, indices);
    if (!lin || !isRegular(lin->JtJ)) return indices;
    const Eigen::Matrix2d JtJ_inv = lin->JtJ.inverse();
    std::vector<double> t(indices.size());
    for (size_t i = 0; i < indices.size(); i++) {
        const double h = lin->J[i].dot(JtJ_inv * lin->J[i]);
        t[i] = std::abs(lin->r[i]) / std::sqrt(std::max(1 - h, kMinOneMinusLeverage));
    }
    std::vector<double> sorted = t;
    const auto mid = sorted.begin() + std::ptrdiff_t(sorted.size() / 2);
    std::nth_element(sorted.begin(), mid, sorted.end());
    const double limit = 3 * 1.4826 * *mid;
    std::vector<size_t> kept;
    for (size_t i = 0; i < indices.size(); i++)
        if (t[i] <= limit) kept.push_back(indices[i]);
    return kept;
}

}  // namespace

void OmniViewObserver::TOptions::validate() const
{
    constexpr const char* kOwner = "OmniViewObserver";
    matching.validate();
    ransac.validate();
    requireParameter(min_sigma_phi >= 0 && min_sigma_phi < M_PI / 2, kOwner, "min_sigma_phi_deg",
                     mrpt::RAD2DEG(min_sigma_phi), "must be in [0, 90)");
    requireParameter(min_sigma_beta >= 0 && min_sigma_beta < M_PI / 2, kOwner, "min_sigma_beta_deg",
                     mrpt::RAD2DEG(min_sigma_beta), "must be in [0, 90)");
}

void OmniViewObserver::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                    const std::string& section)
{
    matching.loadFromConfigFile(cfg, section);
    ransac.loadFromConfigFile(cfg, section);
    min_sigma_phi =
        mrpt::DEG2RAD(cfg.read_double(section, "min_sigma_phi_deg", mrpt::RAD2DEG(min_sigma_phi)));
    min_sigma_beta = mrpt::DEG2RAD(
        cfg.read_double(section, "min_sigma_beta_deg", mrpt::RAD2DEG(min_sigma_beta)));
    validate();
}

void OmniViewObserver::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                                  const std::string& s) const
{
    matching.saveToConfigFile(c, s);
    ransac.saveToConfigFile(c, s);
    MRPT_SAVE_CONFIG_VAR_DEGREES_COMMENT("min_sigma_phi_deg", min_sigma_phi,
                                         "[deg] floor of the standard deviation of phi in R");
    MRPT_SAVE_CONFIG_VAR_DEGREES_COMMENT("min_sigma_beta_deg", min_sigma_beta,
                                         "[deg] floor of the standard deviation of beta in R");
}

OmniViewObserver::OmniViewObserver() : OmniViewObserver(TOptions()) {}

OmniViewObserver::OmniViewObserver(const TOptions& options)
    : m_options(options), m_matcher(options.matching), m_ransac(options.ransac)
{
    m_options.validate();
}

ViewFeatureMatcher::TResult OmniViewObserver::match(const TViewFeatures& current,
                                                    const TViewFeatures& view,
                                                    const TPrediction& prediction) const
{
    return m_matcher.match(current, view, prediction);
}

std::optional<OmniViewObserver::TLeastSquares> OmniViewObserver::refine(
    const TViewObservation& start, const Eigen::Matrix3Xd& rays_v, const Eigen::Matrix3Xd& rays_l,
    const std::vector<size_t>& indices)
{
    PlanarEssentialMatrix::checkRays(rays_v, rays_l);
    if (indices.size() < 3) return std::nullopt;
    TViewObservation z = start;
    for (int iteration = 0;; iteration++) {
        const auto lin = linearize(z, rays_v, rays_l, indices);
        if (!lin || !isRegular(lin->JtJ)) return std::nullopt;
        Eigen::Vector2d Jtr = Eigen::Vector2d::Zero();
        double sum2 = 0;
        for (size_t i = 0; i < indices.size(); i++) {
            Jtr += lin->J[i] * lin->r[i];
            sum2 += lin->r[i] * lin->r[i];
        }
        const Eigen::Matrix2d JtJ_inv = lin->JtJ.inverse();
        const Eigen::Vector2d delta = -JtJ_inv * Jtr;
        if (iteration == kMaxIterations || delta.norm() < kConverged) {
            return TLeastSquares{z, sum2 / double(indices.size() - 2) * JtJ_inv,
                                 std::sqrt(sum2 / double(indices.size()))};
        }
        z.phi = mrpt::math::wrapToPi(z.phi + delta(0));
        z.beta = mrpt::math::wrapToPi(z.beta + delta(1));
    }
}

std::optional<OmniViewObserver::TObservation> OmniViewObserver::observe(
    const TViewFeatures& current, const TViewFeatures& view, const TPrediction& prediction,
    mrpt::random::CRandomGenerator& rng) const
{
    const ViewFeatureMatcher::TResult matched = m_matcher.match(current, view, prediction);
    const size_t n = matched.matches.size();
    if (n < size_t(m_options.ransac.min_inliers)) return std::nullopt;
    Eigen::Matrix3Xd rays_v(3, Eigen::Index(n)), rays_l(3, Eigen::Index(n));
    for (size_t i = 0; i < n; i++) {
        rays_v.col(Eigen::Index(i)) = current.rays.col(matched.matches[i].current);
        rays_l.col(Eigen::Index(i)) = view.rays.col(matched.matches[i].view);
    }
    const auto robust = m_ransac.estimate(rays_v, rays_l, rng);
    if (!robust) return std::nullopt;

    std::vector<size_t> inliers;
    for (size_t i = 0; i < n; i++)
        if (robust->inliers[i]) inliers.push_back(i);
    // Refinement, then the inliers re-selected at 3 σ̂ of their studentized residuals around
    // the refined motion until stable.
    std::optional<TLeastSquares> ls;
    TViewObservation start = robust->observation;
    for (int round = 0;; round++) {
        ls = refine(start, rays_v, rays_l, inliers);
        if (!ls) return std::nullopt;
        if (round == kMaxReselections) break;
        const std::vector<size_t> kept = studentizedInliers(ls->z, rays_v, rays_l, inliers);
        if (kept.size() == inliers.size() || kept.size() < size_t(m_options.ransac.min_inliers))
            break;
        inliers = kept;
        start = ls->z;
    }

    TObservation o;
    o.z = ls->z;
    o.candidates_compared = matched.candidates_compared;
    o.matches = n;
    o.inliers = inliers.size();
    o.rms_residual = ls->rms_residual;
    o.median_parallax = robust->median_parallax;
    for (size_t i : inliers) {
        o.inlier_current.push_back(matched.matches[i].current);
        o.inlier_view.push_back(matched.matches[i].view);
    }
    // Floors on the standard deviations, same correlation.
    const Eigen::Vector2d sigma = ls->covariance.diagonal().cwiseSqrt();
    const double rho = sigma(0) * sigma(1) > 0 ? ls->covariance(0, 1) / (sigma(0) * sigma(1)) : 0.0;
    const Eigen::Vector2d floored(std::max(sigma(0), m_options.min_sigma_phi),
                                  std::max(sigma(1), m_options.min_sigma_beta));
    o.R << floored(0) * floored(0), rho * floored(0) * floored(1), rho * floored(0) * floored(1),
        floored(1) * floored(1);
    return o;
}

}  // namespace mrpt_vslam::viewmap
