#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/Median.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/viewmap/PlanarEssentialRansac.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::viewmap {

using core::requireParameter;

namespace {

constexpr size_t kSampleSize = 4;  // matches per minimal sample
constexpr int kMaxRefits = 10;     // bound on the refits of one local optimisation

/** A model with its MSAC cost Σ min(r², τ²) and its inliers: the matches with r ≤ τ whose
 *  depths are not negative for the majority's direction of translation (cheirality). */
struct THypothesis {
    PlanarEssentialMatrix essential;
    double cost = 0;
    std::vector<size_t> inliers;
};

THypothesis score(const PlanarEssentialMatrix& E, const Eigen::Matrix3Xd& rays_v,
                  const Eigen::Matrix3Xd& rays_l, double tau)
{
    struct TClose {
        size_t index;
        double r2;
        int sign;
    };
    std::vector<TClose> close;
    size_t front = 0, behind = 0;
    for (Eigen::Index k = 0; k < rays_v.cols(); k++) {
        const double r = E.residual(rays_v.col(k), rays_l.col(k));
        if (!(r <= tau)) continue;
        const int sign = E.depthSign(rays_v.col(k), rays_l.col(k));
        close.push_back({size_t(k), r * r, sign});
        front += sign > 0;
        behind += sign < 0;
    }
    const int wrong_sign = front >= behind ? -1 : 1;
    THypothesis h{E, 0, {}};
    for (const auto& c : close) {
        if (c.sign == wrong_sign) continue;
        h.inliers.push_back(c.index);
        h.cost += c.r2;
    }
    h.cost += double(size_t(rays_v.cols()) - h.inliers.size()) * tau * tau;
    return h;
}

/** Local optimisation (Chum, Matas & Kittler 2003): refit on the inliers while the cost drops.
 *  Minimal samples are noisy, so this is what brings a good sample to the best model. */
THypothesis refineOnInliers(THypothesis h, const Eigen::Matrix3Xd& rays_v,
                            const Eigen::Matrix3Xd& rays_l, double tau)
{
    for (int round = 0; round < kMaxRefits; round++) {
        const auto refit = PlanarEssentialMatrix::fit(rays_v, rays_l, h.inliers);
        if (!refit) break;
        THypothesis next = score(*refit, rays_v, rays_l, tau);
        if (!(next.cost < h.cost)) break;
        const bool stable = next.inliers == h.inliers;
        h = std::move(next);
        if (stable) break;
    }
    return h;
}

/// 4 distinct indices in [0, n).
std::array<size_t, kSampleSize> drawSample(size_t n, mrpt::random::CRandomGenerator& rng)
{
    std::array<size_t, kSampleSize> sample;
    for (size_t i = 0; i < kSampleSize; i++) {
        do {
            rng.drawUniformUnsignedIntRange(sample[i], size_t(0), n - 1);
        } while (std::find(sample.begin(), sample.begin() + i, sample[i]) != sample.begin() + i);
    }
    return sample;
}

/// Samples needed to draw one outlier-free sample with probability `confidence`.
double requiredIterations(double inlier_ratio, double confidence)
{
    const double p_good = std::pow(inlier_ratio, double(kSampleSize));
    if (p_good >= 1) return 0;
    if (p_good <= 0) return std::numeric_limits<double>::infinity();
    return std::log(1 - confidence) / std::log1p(-p_good);
}

}  // namespace

void PlanarEssentialRansac::TOptions::validate() const
{
    constexpr const char* kOwner = "PlanarEssentialRansac";
    requireParameter(inlier_threshold > 0 && inlier_threshold < M_PI / 2, kOwner,
                     "inlier_threshold_deg", mrpt::RAD2DEG(inlier_threshold), "must be in (0, 90)");
    requireParameter(confidence > 0 && confidence < 1, kOwner, "confidence", confidence,
                     "must be in (0, 1)");
    requireParameter(max_iterations >= 1 && max_iterations <= 100000, kOwner, "max_iterations",
                     max_iterations, "must be 1 to 100000");
    requireParameter(min_inliers >= int(kSampleSize), kOwner, "min_inliers", min_inliers,
                     "must be >= 4");
    requireParameter(min_parallax >= 0 && min_parallax < M_PI, kOwner, "min_parallax_deg",
                     mrpt::RAD2DEG(min_parallax), "must be in [0, 180)");
}

void PlanarEssentialRansac::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                         const std::string& section)
{
    inlier_threshold = mrpt::DEG2RAD(
        cfg.read_double(section, "inlier_threshold_deg", mrpt::RAD2DEG(inlier_threshold)));
    MRPT_LOAD_CONFIG_VAR(confidence, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(max_iterations, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(min_inliers, int, cfg, section);
    min_parallax =
        mrpt::DEG2RAD(cfg.read_double(section, "min_parallax_deg", mrpt::RAD2DEG(min_parallax)));
    validate();
}

void PlanarEssentialRansac::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                                       const std::string& s) const
{
    MRPT_SAVE_CONFIG_VAR_DEGREES_COMMENT("inlier_threshold_deg", inlier_threshold,
                                         "[deg] largest epipolar (Sampson) residual of an inlier");
    MRPT_SAVE_CONFIG_VAR_COMMENT(confidence, "probability of one outlier-free RANSAC sample");
    MRPT_SAVE_CONFIG_VAR_COMMENT(max_iterations, "cap on the RANSAC samples");
    MRPT_SAVE_CONFIG_VAR_COMMENT(min_inliers, "fewer inliers: no observation");
    MRPT_SAVE_CONFIG_VAR_DEGREES_COMMENT("min_parallax_deg", min_parallax,
                                         "[deg] smaller median parallax: bearing unobservable");
}

PlanarEssentialRansac::PlanarEssentialRansac() : PlanarEssentialRansac(TOptions()) {}

PlanarEssentialRansac::PlanarEssentialRansac(const TOptions& options) : m_options(options)
{
    m_options.validate();
}

std::optional<PlanarEssentialRansac::TResult> PlanarEssentialRansac::estimate(
    const Eigen::Matrix3Xd& rays_v, const Eigen::Matrix3Xd& rays_l,
    mrpt::random::CRandomGenerator& rng) const
{
    const size_t n = size_t(rays_v.cols());
    PlanarEssentialMatrix::checkRays(rays_v, rays_l);
    if (n < size_t(m_options.min_inliers)) return std::nullopt;
    const double tau = m_options.inlier_threshold;

    // 1-4. RANSAC with MSAC and cheirality scoring, a refit on the inliers of every new best
    // model and an adaptive number of samples.
    std::optional<THypothesis> best;
    size_t iterations = 0;
    double needed = m_options.max_iterations;
    while (iterations < size_t(m_options.max_iterations) && double(iterations) < needed) {
        iterations++;
        const auto sample = drawSample(n, rng);
        const auto E = PlanarEssentialMatrix::fit(rays_v, rays_l, {sample.begin(), sample.end()});
        if (!E) continue;
        THypothesis h = score(*E, rays_v, rays_l, tau);
        if (best && !(h.cost < best->cost)) continue;
        best = refineOnInliers(std::move(h), rays_v, rays_l, tau);
        needed = requiredIterations(double(best->inliers.size()) / n, m_options.confidence);
    }
    if (!best || best->inliers.size() < size_t(m_options.min_inliers)) return std::nullopt;
    const std::vector<size_t>& inliers = best->inliers;

    // 5. φ or φ + π.
    const auto z = best->essential.motion(rays_v, rays_l, inliers);
    if (!z) return std::nullopt;

    // The residual statistic and the parallax are filled in below.
    TResult result{*z,
                   best->essential,
                   std::vector<bool>(n, false),
                   inliers.size(),
                   /*rms_residual*/ 0.0,
                   /*median_parallax*/ 0.0,
                   iterations};
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(z->beta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    std::vector<double> parallax;
    double sum2 = 0;
    for (size_t k : inliers) {
        result.inliers[k] = true;
        const auto col = Eigen::Index(k);
        const double r = best->essential.residual(rays_v.col(col), rays_l.col(col));
        sum2 += r * r;
        const Eigen::Vector3d p_l_in_v = R * rays_l.col(col);
        parallax.push_back(
            std::atan2(rays_v.col(col).cross(p_l_in_v).norm(), rays_v.col(col).dot(p_l_in_v)));
    }
    result.rms_residual = std::sqrt(sum2 / double(inliers.size()));
    result.median_parallax = core::median(parallax);
    // A rotation alone explains the rays: φ is not observable.
    if (result.median_parallax < m_options.min_parallax) return std::nullopt;
    return result;
}

}  // namespace mrpt_vslam::viewmap
