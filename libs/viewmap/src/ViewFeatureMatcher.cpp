#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/viewmap/ViewFeatureMatcher.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mrpt_vslam::viewmap {

using core::requireParameter;

namespace {

/// The 12 edges of the 3 × 3 grid of samples (sample 3·i + j): from kEdgeFrom[e] to kEdgeTo[e].
constexpr std::array<uint8_t, 12> kEdgeFrom{0, 1, 3, 4, 6, 7, 0, 3, 1, 4, 2, 5};
constexpr std::array<uint8_t, 12> kEdgeTo{1, 2, 4, 5, 7, 8, 3, 6, 4, 7, 5, 8};

/// Rays per block of the vectorized area test; the current rays are padded by one block.
constexpr size_t kBlock = 8;

/// Regula falsi steps to the zero of the epipolar constraint along an edge of the grid.
constexpr int kCrossingSteps = 3;

/// Part of the band's half width tried on both sides of an epipolar crossing that is off the arc.
constexpr double kBandReach = 0.9;

/// Below this |t × R p_l| the view ray points along the baseline: no epipolar plane.
constexpr double kMinArcSine = 1e-9;

/// The terms of one sample and one view ray in PredictedSearchArea::test().
struct TSampleTerms {
    float a0, a1, a2;        ///< E_j p_l
    float m0, m1, m2;        ///< middle of the arc
    float norm2, inv_norm2;  ///< |E_j p_l|², its inverse (0: no epipolar plane)
    float cos_half;          ///< cos(half arc + tolerance)
    float cos_near;          ///< cos(half arc + tolerance + reach), see TViewRay::cos_near
    float tol2;              ///< tolerance²
};

/** One sample of the area test over n current rays (n a multiple of kBlock): c = p_vᵀ E_j p_l;
 *  Sampson residual² = c² / (|E p_l|² + |Eᵀ p_v|² − 2c²) (PlanarEssentialMatrix::residual with
 *  unit rays) ≤ tolerance²; on the arc when the projection q of p_v on the epipolar plane makes
 *  an angle ≤ half arc + tolerance with its middle: d = p_v·mid ≥ cos(half) |q|, with
 *  |q|² = 1 − c² / |E p_l|²; near when that angle is ≤ half arc + tolerance + reach. Keeps the
 *  extremes of c over the samples. Branch-free on unaliased arrays, so that it vectorizes. */
void testSample(size_t n, const float* __restrict x, const float* __restrict y,
                const float* __restrict z, const float* __restrict et_pv2, const TSampleTerms& t,
                float* __restrict c_out, float* __restrict c_min, float* __restrict c_max,
                int32_t* __restrict inside, int32_t* __restrict near)
{
    n &= ~(kBlock - 1);
    const float a0 = t.a0, a1 = t.a1, a2 = t.a2, m0 = t.m0, m1 = t.m1, m2 = t.m2;
    const float norm2 = t.norm2, inv_norm2 = t.inv_norm2, tol2 = t.tol2;
    const float band_scale = 1 + 2 * tol2, cos_half2 = t.cos_half * t.cos_half;
    const bool obtuse = t.cos_half < 0;
    const float cos_near2 = t.cos_near * t.cos_near;
    const bool obtuse_near = t.cos_near < 0;
    for (size_t k = 0; k < n; k++) {
        const float c = a0 * x[k] + a1 * y[k] + a2 * z[k];
        const float c2 = c * c;
        const float q2 = std::max(0.0f, 1 - c2 * inv_norm2);
        const float d = m0 * x[k] + m1 * y[k] + m2 * z[k];
        const float d2 = d * d, h2q2 = cos_half2 * q2;
        const bool arc = ((d >= 0) & (obtuse | (d2 >= h2q2))) | (obtuse & (d2 <= h2q2));
        const bool band = c2 * band_scale <= tol2 * (norm2 + et_pv2[k]);
        c_out[k] = c;
        c_min[k] = std::min(c_min[k], c);
        c_max[k] = std::max(c_max[k], c);
        const float n2q2 = cos_near2 * q2;
        const bool near_arc =
            ((d >= 0) & (obtuse_near | (d2 >= n2q2))) | (obtuse_near & (d2 <= n2q2));
        inside[k] |= int32_t(band & arc);
        near[k] |= int32_t(near_arc);
    }
}

void checkPrediction(const TPrediction& p)
{
    if (!std::isfinite(p.z.phi) || !std::isfinite(p.z.beta)) {
        throw std::invalid_argument("PredictedSearchArea: the predicted observation is not finite");
    }
    const double scale = p.S.cwiseAbs().maxCoeff();
    if (!p.S.allFinite() || std::abs(p.S(0, 1) - p.S(1, 0)) > 1e-12 * std::max(scale, 1e-300)) {
        throw std::invalid_argument("PredictedSearchArea: S is not a finite symmetric matrix");
    }
    if (p.S(0, 0) < 0 || p.S(1, 1) < 0 || p.S.determinant() < -1e-12 * scale * scale) {
        throw std::invalid_argument("PredictedSearchArea: S is not positive semi-definite");
    }
}

/** Squared descriptor distance, stopping once it exceeds `bound2` (the partial sum is returned
 *  then). Sixteen independent accumulators so that the loop vectorizes. */
float distance2Bounded(const core::USurfDescriptor::TDescriptor& a,
                       const core::USurfDescriptor::TDescriptor& b, float bound2)
{
    constexpr size_t kChunk = 16;
    std::array<float, kChunk> acc{};
    float sum = 0;
    for (size_t start = 0; start < core::USurfDescriptor::kSize; start += kChunk) {
        for (size_t i = 0; i < kChunk; i++) {
            const float d = a[start + i] - b[start + i];
            acc[i] += d * d;
        }
        sum = 0;
        for (float v : acc) sum += v;
        if (sum > bound2) break;
    }
    return sum;
}

void checkFeatures(const TViewFeatures& f, const char* which)
{
    if (size_t(f.rays.cols()) != f.size() || f.laplacian_signs.size() != f.size()) {
        throw std::invalid_argument(mrpt::format(
            "ViewFeatureMatcher: the %s features have %zu descriptors, %d rays and %zu "
            "Laplacian signs",
            which, f.size(), int(f.rays.cols()), f.laplacian_signs.size()));
    }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// PredictedSearchArea

PredictedSearchArea::PredictedSearchArea(const TPrediction& prediction, double search_sigmas,
                                         double tolerance)
    : m_tolerance(tolerance),
      m_cos_tolerance(std::cos(tolerance)),
      m_sin_tolerance(std::sin(tolerance))
{
    checkPrediction(prediction);
    if (!(search_sigmas >= 0) || !std::isfinite(search_sigmas)) {
        throw std::invalid_argument(
            mrpt::format("PredictedSearchArea: search_sigmas = %g must be >= 0", search_sigmas));
    }
    if (!(tolerance > 0 && tolerance < M_PI / 2)) {
        throw std::invalid_argument(mrpt::format(
            "PredictedSearchArea: tolerance = %g rad must be in (0, pi/2)", tolerance));
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(prediction.S);
    const Eigen::Vector2d half_extent =
        search_sigmas * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();  // k σ per eigenvector
    m_whole_sphere = half_extent.maxCoeff() >= M_PI / 2;
    // Half the spans of the hull in φ and β plus the tolerance: any motion of the hull is within a
    // quarter of the spans of a sample, and its arc moves by at most twice that.
    const Eigen::Matrix2d corners = eig.eigenvectors() * half_extent.asDiagonal();
    m_reach = corners.row(0).cwiseAbs().sum() + corners.row(1).cwiseAbs().sum() + tolerance;
    const Eigen::Vector2d z0(prediction.z.phi, prediction.z.beta);
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            const size_t s = size_t(3 * i + j);
            const Eigen::Vector2d z = z0 + (i - 1) * half_extent(0) * eig.eigenvectors().col(0) +
                                      (j - 1) * half_extent(1) * eig.eigenvectors().col(1);
            m_samples[s] = {mrpt::math::wrapToPi(z(0)), mrpt::math::wrapToPi(z(1))};
            m_E[s] = PlanarEssentialMatrix::fromMotion(z(0), z(1)).matrix();
            m_t[s] = Eigen::Vector3d(std::cos(z(0)), std::sin(z(0)), 0);
            m_R[s] = Eigen::AngleAxisd(z(1), Eigen::Vector3d::UnitZ()).toRotationMatrix();
        }
    }
}

PredictedSearchArea::TCurrentRays PredictedSearchArea::prepareCurrent(
    const Eigen::Matrix3Xd& rays) const
{
    const size_t n = size_t(rays.cols());
    TCurrentRays c;
    c.x.assign(n + kBlock, 0), c.y.assign(n + kBlock, 0), c.z.assign(n + kBlock, 0);
    for (auto& v : c.et_pv2) v.assign(n + kBlock, 0);
    for (size_t k = 0; k < n; k++) {
        const auto p = rays.col(Eigen::Index(k));
        c.x[k] = float(p.x()), c.y[k] = float(p.y()), c.z[k] = float(p.z());
        for (size_t s = 0; s < kSamples; s++) {
            // E_jᵀ p_v = (E31 z, E32 z, E13 x + E23 y).
            const Eigen::Matrix3d& E = m_E[s];
            const double w = E(0, 2) * p.x() + E(1, 2) * p.y();
            c.et_pv2[s][k] = float((E(2, 0) * E(2, 0) + E(2, 1) * E(2, 1)) * p.z() * p.z() + w * w);
        }
    }
    return c;
}

PredictedSearchArea::TViewRay PredictedSearchArea::prepareView(const Eigen::Vector3d& p_l) const
{
    TViewRay v;
    v.p_l = p_l;
    for (size_t s = 0; s < kSamples; s++) {
        v.r[s] = m_R[s] * p_l;
        const Eigen::Vector3d a = m_E[s] * p_l;  // ∝ t × R p_l: normal of the epipolar plane
        const Eigen::Vector3d& r = v.r[s];       // direction at infinity
        const Eigen::Vector3d& t = m_t[s];       // epipole
        const double sin_alpha = t.cross(r).norm(), cos_alpha = t.dot(r);
        if (!(sin_alpha > kMinArcSine)) {
            // p_l along the baseline: no epipolar plane, nothing inside for this sample.
            v.e_pl[s] = {0, 0, 0};
            v.e_pl2[s] = v.inv_e_pl2[s] = 0;
            v.mid[s] = {0, 0, 0};
            v.cos_half[s] = v.cos_near[s] = 1;
            continue;
        }
        // The arc from t (angle 0) to r (angle α) in its plane, u ⊥ t towards r.
        const double alpha = std::atan2(sin_alpha, cos_alpha);
        const Eigen::Vector3d u = (r - cos_alpha * t) / sin_alpha;
        const Eigen::Vector3d mid = std::cos(alpha / 2) * t + std::sin(alpha / 2) * u;
        v.e_pl[s] = {float(a.x()), float(a.y()), float(a.z())};
        v.e_pl2[s] = float(a.squaredNorm());
        v.inv_e_pl2[s] = float(1 / a.squaredNorm());
        v.mid[s] = {float(mid.x()), float(mid.y()), float(mid.z())};
        v.cos_half[s] = float(std::cos(alpha / 2 + m_tolerance));
        v.cos_near[s] = float(std::cos(std::min(M_PI, alpha / 2 + m_tolerance + m_reach)));
    }
    return v;
}

void PredictedSearchArea::testSamples(const TCurrentRays& current, size_t begin, size_t end,
                                      const TViewRay& l, TWorkspace& ws) const
{
    const size_t n = end - begin;
    ws.inside.assign(n, m_whole_sphere ? 1 : 0);
    ws.near.assign(n, 0);
    if (m_whole_sphere) return;
    // Whole blocks (the current rays are padded): a trip count the compiler knows to be a
    // multiple of the vector width.
    const size_t n_blocks = (n + kBlock - 1) & ~(kBlock - 1);
    ws.inside.resize(n_blocks, 0);
    ws.near.resize(n_blocks, 0);
    ws.c_min.assign(n_blocks, std::numeric_limits<float>::infinity());
    ws.c_max.assign(n_blocks, -std::numeric_limits<float>::infinity());
    const float tol2 = float(m_tolerance * m_tolerance);
    const float* x = current.x.data() + begin;
    const float* y = current.y.data() + begin;
    const float* z = current.z.data() + begin;
    int32_t* inside = ws.inside.data();

    for (size_t s = 0; s < kSamples; s++) {
        ws.c[s].resize(n_blocks);
        testSample(n_blocks, x, y, z, current.et_pv2[s].data() + begin,
                   {l.e_pl[s][0], l.e_pl[s][1], l.e_pl[s][2], l.mid[s][0], l.mid[s][1], l.mid[s][2],
                    l.e_pl2[s], l.inv_e_pl2[s], l.cos_half[s], l.cos_near[s], tol2},
                   ws.c[s].data(), ws.c_min.data(), ws.c_max.data(), inside, ws.near.data());
    }
    ws.inside.resize(n);
    ws.near.resize(n);
}

bool PredictedSearchArea::needsFilling(const TWorkspace& ws, size_t i)
{
    return !ws.inside[i] && ws.near[i] && ws.c_min[i] < 0 && ws.c_max[i] > 0;
}

bool PredictedSearchArea::betweenSamples(const TCurrentRays& current, size_t begin, size_t i,
                                         const TViewRay& l, const TWorkspace& ws) const
{
    // When c changes sign along an edge, the pair is exactly epipolar for a motion there. The
    // grid is connected, so some edge changes sign exactly when c takes both signs over the
    // samples (needsFilling()).
    const Eigen::Vector3d p_v(current.x[begin + i], current.y[begin + i], current.z[begin + i]);
    for (size_t e = 0; e < kEdgeFrom.size(); e++) {
        const size_t s0 = kEdgeFrom[e], s1 = kEdgeTo[e];
        const float c0 = ws.c[s0][i], c1 = ws.c[s1][i];
        if (!(c0 * c1 < 0)) continue;
        // The motion at w ∈ [0, 1] along the edge, by interpolation of the epipoles and of
        // the directions at infinity (a rotation of p_l about z keeps its horizontal length).
        Eigen::Vector3d t, r;
        const auto motionAt = [&](double w) {
            t = ((1 - w) * m_t[s0] + w * m_t[s1]).normalized();
            r = (1 - w) * l.r[s0] + w * l.r[s1];
            if (const double h = r.head<2>().norm(); h > 0)
                r.head<2>() *= l.p_l.head<2>().norm() / h;
            r.z() = l.p_l.z();
            return p_v.dot(t.cross(r)) / M_SQRT2;  // c = p_vᵀ E p_l
        };
        // Towards the zero of c on the edge by regula falsi (Illinois variant) while the
        // motion reached is not epipolar enough for the band.
        double w_lo = 0, w_hi = 1, c_lo = c0, c_hi = c1;
        int kept_side = 0;
        TArcTest result = TArcTest::OffBand;
        double w = 0;
        for (int step = 0; result == TArcTest::OffBand && step <= kCrossingSteps; step++) {
            w = (w_lo * c_hi - w_hi * c_lo) / (c_hi - c_lo);
            const double c = motionAt(w);
            result = arcTest(t, r, p_v);
            if ((c < 0) == (c_lo < 0)) {
                w_lo = w, c_lo = c;
                if (kept_side == 1) c_hi /= 2;
                kept_side = 1;
            } else {
                w_hi = w, c_hi = c;
                if (kept_side == -1) c_lo /= 2;
                kept_side = -1;
            }
        }
        // Epipolar but off the arc: the band around the crossing may still reach the arc
        // where the arc has moved. Its ends on the edge: |c| = tolerance × the Sampson
        // denominator, to first order.
        if (result == TArcTest::OffArc) {
            const double half_band = kBandReach * m_tolerance * sampsonDenominator(t, r, p_v) /
                                     std::abs(double(c1) - double(c0));
            for (const double w_end : {w - half_band, w + half_band}) {
                motionAt(std::clamp(w_end, 0.0, 1.0));
                if (arcTest(t, r, p_v) == TArcTest::Inside) {
                    result = TArcTest::Inside;
                    break;
                }
            }
        }
        if (result == TArcTest::Inside) return true;
    }
    return false;
}

const std::vector<int32_t>& PredictedSearchArea::test(const TCurrentRays& current, size_t begin,
                                                      size_t end, const TViewRay& l,
                                                      TWorkspace& ws) const
{
    testSamples(current, begin, end, l, ws);
    for (size_t i = 0; i < end - begin; i++) {
        if (needsFilling(ws, i) && betweenSamples(current, begin, i, l, ws)) ws.inside[i] = 1;
    }
    return ws.inside;
}

double PredictedSearchArea::sampsonDenominator(const Eigen::Vector3d& t, const Eigen::Vector3d& r,
                                               const Eigen::Vector3d& p_v)
{
    // |E p_l|² + |Eᵀ p_v|² − 2c² with E = [t]× R_z / √2: |t × r|² / 2 + |t × p_v|² / 2 − 2c².
    const double c = p_v.dot(t.cross(r)) / M_SQRT2;
    return std::sqrt(
        std::max(0.0, 0.5 * (t.cross(r).squaredNorm() + t.cross(p_v).squaredNorm()) - 2 * c * c));
}

PredictedSearchArea::TArcTest PredictedSearchArea::arcTest(const Eigen::Vector3d& t,
                                                           const Eigen::Vector3d& r,
                                                           const Eigen::Vector3d& p_v) const
{
    const Eigen::Vector3d normal = t.cross(r);  // √2 E p_l
    const double sin_alpha = normal.norm(), cos_alpha = t.dot(r);
    if (!(sin_alpha > kMinArcSine)) return TArcTest::OffArc;
    // Sampson residual² = c² / (|E p_l|² + |Eᵀ p_v|² − 2c²).
    const double c = p_v.dot(normal) / M_SQRT2;
    if (!(std::abs(c) <= m_tolerance * sampsonDenominator(t, r, p_v))) return TArcTest::OffBand;
    // The projection q of p_v on the plane within half the arc + tolerance of its middle.
    const Eigen::Vector3d u = (r - cos_alpha * t) / sin_alpha;
    const double cos_half = std::sqrt(0.5 * (1 + cos_alpha));
    const double sin_half = std::sqrt(0.5 * (1 - cos_alpha));
    const Eigen::Vector3d mid = cos_half * t + sin_half * u;
    const double q_norm = std::sqrt(std::max(0.0, 1 - 2 * c * c / (sin_alpha * sin_alpha)));
    const double cos_limit = cos_half * m_cos_tolerance - sin_half * m_sin_tolerance;
    return p_v.dot(mid) >= cos_limit * q_norm ? TArcTest::Inside : TArcTest::OffArc;
}

bool PredictedSearchArea::contains(const Eigen::Vector3d& p_v, const Eigen::Vector3d& p_l) const
{
    TWorkspace ws;
    return test(prepareCurrent(p_v), 0, 1, prepareView(p_l), ws)[0] != 0;
}

// ---------------------------------------------------------------------------------------------
// ViewFeatureMatcher

void ViewFeatureMatcher::TOptions::validate() const
{
    constexpr const char* kOwner = "ViewFeatureMatcher";
    requireParameter(search_sigmas >= 0 && std::isfinite(search_sigmas), kOwner, "search_sigmas",
                     search_sigmas, "must be >= 0");
    requireParameter(area_tolerance > 0 && area_tolerance < M_PI / 2, kOwner, "area_tolerance_deg",
                     mrpt::RAD2DEG(area_tolerance), "must be in (0, 90)");
    requireParameter(max_ratio > 0 && max_ratio <= 1, kOwner, "max_ratio", max_ratio,
                     "must be in (0, 1]");
    requireParameter(max_descriptor_distance > 0 && std::isfinite(max_descriptor_distance), kOwner,
                     "max_descriptor_distance", max_descriptor_distance, "must be > 0");
}

void ViewFeatureMatcher::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                      const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(search_sigmas, double, cfg, section);
    area_tolerance = mrpt::DEG2RAD(
        cfg.read_double(section, "area_tolerance_deg", mrpt::RAD2DEG(area_tolerance)));
    MRPT_LOAD_CONFIG_VAR(max_ratio, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(max_descriptor_distance, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(restrict_search_area, bool, cfg, section);
    validate();
}

void ViewFeatureMatcher::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                                    const std::string& s) const
{
    MRPT_SAVE_CONFIG_VAR_COMMENT(search_sigmas, "predicted area: motions within +-k sigma of S");
    MRPT_SAVE_CONFIG_VAR_DEGREES_COMMENT("area_tolerance_deg", area_tolerance,
                                         "[deg] width of the predicted area around its arcs");
    MRPT_SAVE_CONFIG_VAR_COMMENT(max_ratio, "Lowe's ratio: nearest < ratio x second nearest");
    MRPT_SAVE_CONFIG_VAR_COMMENT(max_descriptor_distance, "largest descriptor distance of a match");
    MRPT_SAVE_CONFIG_VAR_COMMENT(restrict_search_area,
                                 "search only the predicted area (false: the whole image)");
}

ViewFeatureMatcher::ViewFeatureMatcher() : ViewFeatureMatcher(TOptions()) {}

ViewFeatureMatcher::ViewFeatureMatcher(const TOptions& options) : m_options(options)
{
    m_options.validate();
}

ViewFeatureMatcher::TResult ViewFeatureMatcher::match(const TViewFeatures& current,
                                                      const TViewFeatures& view,
                                                      const TPrediction& prediction) const
{
    checkFeatures(current, "current");
    checkFeatures(view, "view");
    const PredictedSearchArea area(prediction, m_options.search_sigmas, m_options.area_tolerance);
    const bool restrict = m_options.restrict_search_area && !area.wholeSphere();

    // Current points grouped by the sign of the Laplacian: +1 in [0, n_pos), −1 after.
    const size_t n = current.size();
    std::vector<uint32_t> order;
    order.reserve(n);
    for (int sign : {1, -1})
        for (size_t k = 0; k < n; k++)
            if ((current.laplacian_signs[k] > 0) == (sign > 0)) order.push_back(uint32_t(k));
    const size_t n_pos =
        size_t(std::count_if(current.laplacian_signs.begin(), current.laplacian_signs.end(),
                             [](int8_t s) { return s > 0; }));
    PredictedSearchArea::TCurrentRays rays;
    if (restrict) {
        Eigen::Matrix3Xd ordered(3, Eigen::Index(n));
        for (size_t i = 0; i < n; i++) ordered.col(Eigen::Index(i)) = current.rays.col(order[i]);
        rays = area.prepareCurrent(ordered);
    }

    // Nearest neighbour of each view point; the current point keeps its nearest claimant.
    const float max_d2 =
        float(m_options.max_descriptor_distance * m_options.max_descriptor_distance);
    const float ratio2 = float(m_options.max_ratio * m_options.max_ratio);
    // A second nearest beyond max_distance / ratio cannot fail the ratio test of an acceptable
    // nearest, so distances stop there.
    const float far2 = max_d2 / ratio2;
    std::vector<float> claim_d2(n, std::numeric_limits<float>::infinity());
    std::vector<uint32_t> claim_view(n);
    PredictedSearchArea::TWorkspace ws;
    TResult result;
    for (size_t l = 0; l < view.size(); l++) {
        const bool positive = view.laplacian_signs[l] > 0;
        const size_t begin = positive ? 0 : n_pos, end = positive ? n_pos : n;
        if (begin == end) continue;
        PredictedSearchArea::TViewRay view_ray;
        if (restrict) {
            view_ray = area.prepareView(view.rays.col(Eigen::Index(l)));
            area.testSamples(rays, begin, end, view_ray, ws);
        }
        float d1 = std::numeric_limits<float>::infinity(), d2 = far2;
        size_t best = 0;
        for (size_t i = begin; i < end; i++) {
            // Inside at a sample, or maybe between samples: that test, costlier, is only made
            // for a point that would be among the two nearest.
            const bool maybe = restrict && PredictedSearchArea::needsFilling(ws, i - begin);
            if (restrict && !ws.inside[i - begin] && !maybe) continue;
            result.candidates_compared++;
            const float d =
                distance2Bounded(view.descriptors[l], current.descriptors[order[i]], d2);
            if (!(d < d2)) continue;  // not among the two nearest
            if (maybe && !area.betweenSamples(rays, begin, i - begin, view_ray, ws)) continue;
            if (d < d1) {
                d2 = std::min(d1, far2);
                d1 = d;
                best = order[i];
            } else if (d < d2) {
                d2 = d;
            }
        }
        if (!(d1 <= max_d2) || !(d1 < ratio2 * d2)) continue;
        if (d1 < claim_d2[best]) {
            claim_d2[best] = d1;
            claim_view[best] = uint32_t(l);
        }
    }
    for (size_t k = 0; k < n; k++) {
        if (std::isfinite(claim_d2[k])) {
            result.matches.push_back({uint32_t(k), claim_view[k], std::sqrt(claim_d2[k])});
        }
    }
    return result;
}

}  // namespace mrpt_vslam::viewmap
