// The predicted search area, the matcher and the observer on synthetic rays (no rendering):
// the area against a brute-force definition, matching with repeated descriptors, and the
// recovered (φ, β) with the consistency of its R.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/UnifiedSphereCamera.h>
#include <mrpt_vslam/test/PlanarScene.h>
#include <mrpt_vslam/viewmap/OmniViewObserver.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using mrpt::DEG2RAD;
using mrpt::random::CRandomGenerator;
using mrpt_vslam::viewmap::OmniViewObserver;
using mrpt_vslam::viewmap::PlanarEssentialMatrix;
using mrpt_vslam::viewmap::PredictedSearchArea;
using mrpt_vslam::viewmap::predictViewObservation;
using mrpt_vslam::viewmap::TPrediction;
using mrpt_vslam::viewmap::TViewFeatures;
using mrpt_vslam::viewmap::TViewObservation;
using mrpt_vslam::viewmap::ViewFeatureMatcher;
namespace scene_gen = mrpt_vslam::viewmap::test;

namespace {

Eigen::Vector3d randomUnit(CRandomGenerator& rng)
{
    Eigen::Vector3d v;
    do {
        v = Eigen::Vector3d(rng.drawGaussian1D_normalized(), rng.drawGaussian1D_normalized(),
                            rng.drawGaussian1D_normalized());
    } while (v.norm() < 1e-3);
    return v.normalized();
}

Eigen::Matrix3d rotZ(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).matrix(); }

/// Direction from the robot of the view point λ p_l for the motion z (baseline 1).
Eigen::Vector3d seenFromRobot(const TViewObservation& z, const Eigen::Vector3d& p_l, double lambda)
{
    return (rotZ(z.beta) * (lambda * p_l) + Eigen::Vector3d(std::cos(z.phi), std::sin(z.phi), 0))
        .normalized();
}

/** Brute-force membership for one motion z and tolerance τ: Sampson residual ≤ τ and the
 *  projection of p_v on the epipolar plane within [−τ, α + τ] of the arc from the epipole t
 *  (angle 0) to R_z(β) p_l (angle α). */
bool onArc(const TViewObservation& z, const Eigen::Vector3d& p_v, const Eigen::Vector3d& p_l,
           double tau)
{
    const auto E = PlanarEssentialMatrix::fromMotion(z.phi, z.beta);
    if (!(E.residual(p_v, p_l) <= tau)) return false;
    const Eigen::Vector3d t(std::cos(z.phi), std::sin(z.phi), 0), r = rotZ(z.beta) * p_l;
    const Eigen::Vector3d n = t.cross(r).normalized(), u = n.cross(t);
    const double alpha = std::atan2(t.cross(r).norm(), t.dot(r));
    const double psi = std::atan2(p_v.dot(u), p_v.dot(t));
    return psi >= -tau && psi <= alpha + tau;
}

/// A motion of the square hull of the samples, (a, b) ∈ [−1, 1]² in units of k σ.
TViewObservation hullMotion(const TPrediction& p, double k, double a, double b)
{
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(p.S);
    const Eigen::Vector2d s = k * eig.eigenvalues().cwiseMax(0).cwiseSqrt();
    const Eigen::Vector2d z = Eigen::Vector2d(p.z.phi, p.z.beta) +
                              a * s(0) * eig.eigenvectors().col(0) +
                              b * s(1) * eig.eigenvectors().col(1);
    return {z(0), z(1)};
}

/// Brute force over an n × n grid of the hull scaled by `scale`.
bool inHull(const TPrediction& p, double k, double scale, const Eigen::Vector3d& p_v,
            const Eigen::Vector3d& p_l, double tau, int n = 41)
{
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) {
            const double a = scale * (2.0 * i / (n - 1) - 1), b = scale * (2.0 * j / (n - 1) - 1);
            if (onArc(hullMotion(p, k, a, b), p_v, p_l, tau)) return true;
        }
    }
    return false;
}

/// A random prediction with standard deviations in [lo, hi] [rad] and a random correlation.
TPrediction randomPrediction(CRandomGenerator& rng, double lo, double hi)
{
    TPrediction p;
    p.z = {rng.drawUniform(-M_PI, M_PI), rng.drawUniform(-M_PI, M_PI)};
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(rng.drawUniform(0, M_PI)).matrix();
    const Eigen::Vector2d sigma(rng.drawUniform(lo, hi), rng.drawUniform(lo, hi));
    p.S = R * sigma.cwiseAbs2().asDiagonal() * R.transpose();
    p.S(1, 0) = p.S(0, 1);
    return p;
}

/// A view ray as in the office scenes: elevation within [−15°, 60°].
Eigen::Vector3d randomViewRay(CRandomGenerator& rng)
{
    const double az = rng.drawUniform(-M_PI, M_PI), el = DEG2RAD(rng.drawUniform(-15.0, 60.0));
    return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

/** Matched features of a random scene: one random descriptor per point, shared by both images
 *  up to noise; the last `wrong` current points swap descriptors in pairs (wrong matches).
 *  Rays measured by the default omni camera with σ px of noise. */
struct TSynthetic {
    TViewFeatures current, view;
    TViewObservation truth;
};

TViewFeatures emptyFeatures(size_t n)
{
    TViewFeatures f;
    f.pixels = Eigen::Matrix2Xf::Zero(2, Eigen::Index(n));
    f.scales.assign(n, 2.0f);
    f.laplacian_signs.assign(n, 1);
    f.rays.resize(3, Eigen::Index(n));
    f.descriptors.resize(n);
    return f;
}

mrpt_vslam::core::USurfDescriptor::TDescriptor randomDescriptor(CRandomGenerator& rng)
{
    mrpt_vslam::core::USurfDescriptor::TDescriptor d;
    double n2 = 0;
    for (float& e : d) {
        e = float(rng.drawGaussian1D_normalized());
        n2 += double(e) * e;
    }
    for (float& e : d) e = float(e / std::sqrt(n2));
    return d;
}

mrpt_vslam::core::USurfDescriptor::TDescriptor noisy(
    mrpt_vslam::core::USurfDescriptor::TDescriptor d, double sigma, CRandomGenerator& rng)
{
    for (float& e : d) e += float(rng.drawGaussian1D(0, sigma));
    return d;
}

TSynthetic synthetic(CRandomGenerator& rng, size_t n, size_t wrong, double sigma_px)
{
    scene_gen::TSceneOptions opt;
    opt.points = n;
    const auto scene = scene_gen::randomScene(rng, opt);
    const mrpt_vslam::core::UnifiedSphereCamera camera;
    TSynthetic s{emptyFeatures(n), emptyFeatures(n),
                 predictViewObservation(scene.robot, scene.view)};
    for (size_t k = 0; k < n; k++) {
        const auto col = Eigen::Index(k);
        const auto rv = scene_gen::measuredRay(
            camera, scene_gen::rayFrom(scene.robot, scene.points[k]), sigma_px, rng);
        const auto rl = scene_gen::measuredRay(
            camera, scene_gen::rayFrom(scene.view, scene.points[k]), sigma_px, rng);
        EXPECT_TRUE(rv && rl);
        s.current.rays.col(col) = rv.value_or(Eigen::Vector3d::UnitX());
        s.view.rays.col(col) = rl.value_or(Eigen::Vector3d::UnitX());
        const auto d = randomDescriptor(rng);
        s.current.descriptors[k] = noisy(d, 0.01, rng);
        s.view.descriptors[k] = noisy(d, 0.01, rng);
        const int8_t sign = rng.drawUniform(0.0, 1.0) < 0.5 ? 1 : -1;
        s.current.laplacian_signs[k] = s.view.laplacian_signs[k] = sign;
    }
    for (size_t k = n - wrong; k + 1 < n; k += 2) {
        std::swap(s.current.descriptors[k], s.current.descriptors[k + 1]);
        std::swap(s.current.laplacian_signs[k], s.current.laplacian_signs[k + 1]);
    }
    return s;
}

double wrapped(double a) { return std::remainder(a, 2 * M_PI); }

/// The options written to an ini text and read back as a file would be.
mrpt::config::CConfigFileMemory savedAndReparsed(const mrpt::config::CLoadableOptions& o,
                                                 const std::string& section)
{
    mrpt::config::CConfigFileMemory saved;
    o.saveToConfigFile(saved, section);
    std::string text;
    saved.getContent(text);
    return mrpt::config::CConfigFileMemory(text);
}

}  // namespace

// ------------------------------------------------------------------------------------------
// PredictedSearchArea

// With S = 0 the area is exactly the band of the arc from the epipole to R p_l: compared with
// the brute-force definition on 20000 pairs, half of them drawn near the arc, away from the
// boundary (tolerance ± 2 %).
TEST(PredictedSearchArea, ZeroCovarianceIsTheBandOfTheArc)
{
    CRandomGenerator rng(3);
    const double tol = DEG2RAD(1.5);
    int inside = 0, outside = 0, near_boundary = 0;
    for (int trial = 0; trial < 20000; trial++) {
        TPrediction p;
        p.z = {rng.drawUniform(-M_PI, M_PI), rng.drawUniform(-M_PI, M_PI)};
        const PredictedSearchArea area(p, 3.0, tol);
        const Eigen::Vector3d p_l = randomViewRay(rng);
        Eigen::Vector3d p_v = randomUnit(rng);
        if (trial % 2 == 0) {
            // Near the arc: a point at a random depth, moved by up to 3 tolerances.
            const double lambda = std::exp(rng.drawUniform(std::log(0.02), std::log(100.0)));
            p_v = (seenFromRobot(p.z, p_l, lambda) + 3 * tol * randomUnit(rng)).normalized();
        }
        const bool in = onArc(p.z, p_v, p_l, 0.98 * tol), out = !onArc(p.z, p_v, p_l, 1.02 * tol);
        if (!in && !out) {
            near_boundary++;
            continue;
        }
        EXPECT_EQ(area.contains(p_v, p_l), in) << trial;
        inside += in;
        outside += out;
    }
    EXPECT_GT(inside, 3000);
    EXPECT_GT(outside, 10000);
    EXPECT_LT(near_boundary, 1000);
}

// Every point λ p_l (λ from 0.02 to 100 baselines) moved by any motion of the hull of the
// samples lies inside the area: the union over the motions, not only over the 9 samples.
TEST(PredictedSearchArea, ContainsEveryDepthAndMotionOfTheHull)
{
    CRandomGenerator rng(4);
    const double tol = DEG2RAD(1.5);
    int missed = 0, missed_by_samples_only = 0;
    const int trials = 20000;
    for (int trial = 0; trial < trials; trial++) {
        const TPrediction p = randomPrediction(rng, DEG2RAD(0.5), DEG2RAD(8.0));
        const PredictedSearchArea area(p, 3.0, tol);
        const Eigen::Vector3d p_l = randomViewRay(rng);
        const TViewObservation z =
            hullMotion(p, 3.0, rng.drawUniform(-0.95, 0.95), rng.drawUniform(-0.95, 0.95));
        const double lambda = std::exp(rng.drawUniform(std::log(0.02), std::log(100.0)));
        const Eigen::Vector3d p_v = seenFromRobot(z, p_l, lambda);
        if (!area.contains(p_v, p_l)) missed++;
        bool by_samples = false;
        for (const auto& s : area.samples()) by_samples = by_samples || onArc(s, p_v, p_l, tol);
        missed_by_samples_only += !by_samples;
    }
    EXPECT_EQ(missed, 0);
    // The 9 bands alone would miss 12 % of them (measured): the filling between samples matters.
    EXPECT_GT(missed_by_samples_only, trials / 20);
}

// Random pairs against the brute-force union over a 41 × 41 grid of motions: inside the hull
// shrunk to 90 % with half the tolerance ⇒ accepted; accepted ⇒ inside the hull grown to 110 %
// with twice the tolerance.
TEST(PredictedSearchArea, AgreesWithTheBruteForceUnionAwayFromTheBoundary)
{
    CRandomGenerator rng(5);
    const double tol = DEG2RAD(1.5);
    int accepted = 0, rejected = 0, wrong_reject = 0, wrong_accept = 0;
    for (int trial = 0; trial < 600; trial++) {
        const TPrediction p = randomPrediction(rng, DEG2RAD(0.5), DEG2RAD(6.0));
        const PredictedSearchArea area(p, 3.0, tol);
        const Eigen::Vector3d p_l = randomViewRay(rng);
        // Near the area: a point of the hull ±30 % moved by up to 4 tolerances.
        const TViewObservation z =
            hullMotion(p, 3.0, rng.drawUniform(-1.3, 1.3), rng.drawUniform(-1.3, 1.3));
        const double lambda = std::exp(rng.drawUniform(std::log(0.05), std::log(50.0)));
        const Eigen::Vector3d p_v =
            (seenFromRobot(z, p_l, lambda) + 4 * tol * randomUnit(rng)).normalized();
        const bool in = area.contains(p_v, p_l);
        accepted += in;
        rejected += !in;
        if (!in && inHull(p, 3.0, 0.9, p_v, p_l, 0.5 * tol)) wrong_reject++;
        if (in && !inHull(p, 3.0, 1.1, p_v, p_l, 2 * tol)) wrong_accept++;
    }
    EXPECT_GT(accepted, 150);
    EXPECT_GT(rejected, 150);
    EXPECT_EQ(wrong_reject, 0);
    EXPECT_EQ(wrong_accept, 0);
}

// A larger S accepts a superset: a pair inside the area of S away from its boundary (the
// brute-force union with half the tolerance) is inside the area of 4 S. Measured on 4000 pairs
// drawn near the areas: 2 of 2560 such pairs lost (band corners near the arc ends, inside a
// cell of the grid); 19 of the 3183 accepted with S, counting those on the boundary.
TEST(PredictedSearchArea, GrowsWithTheCovariance)
{
    CRandomGenerator rng(6);
    const double tol = DEG2RAD(1.5);
    int small = 0, large = 0, lost = 0, inner = 0, inner_lost = 0;
    for (int trial = 0; trial < 4000; trial++) {
        const TPrediction p = randomPrediction(rng, DEG2RAD(0.3), DEG2RAD(5.0));
        TPrediction wide = p;
        wide.S *= 4;
        const PredictedSearchArea area(p, 3.0, tol), wide_area(wide, 3.0, tol);
        const Eigen::Vector3d p_l = randomViewRay(rng);
        const TViewObservation z =
            hullMotion(wide, 3.0, rng.drawUniform(-1.0, 1.0), rng.drawUniform(-1.0, 1.0));
        const double lambda = std::exp(rng.drawUniform(std::log(0.05), std::log(50.0)));
        const Eigen::Vector3d p_v =
            (seenFromRobot(z, p_l, lambda) + 2 * tol * randomUnit(rng)).normalized();
        const bool in_small = area.contains(p_v, p_l), in_large = wide_area.contains(p_v, p_l);
        small += in_small;
        large += in_large;
        lost += in_small && !in_large;
        if (inHull(p, 3.0, 1.0, p_v, p_l, 0.5 * tol, 21)) {
            inner++;
            inner_lost += !in_large;
        }
    }
    EXPECT_GT(inner, 2000);
    EXPECT_LE(inner_lost, inner / 500);
    EXPECT_LE(lost, small / 100);
    EXPECT_GT(large, small + 400);
}

TEST(PredictedSearchArea, SamplesAndLimits)
{
    TPrediction p;
    p.z = {0.3, -0.2};
    p.S << 4e-4, 0, 0, 1e-4;  // σ = 0.02, 0.01 rad
    const PredictedSearchArea area(p, 3.0, DEG2RAD(1.5));
    EXPECT_FALSE(area.wholeSphere());
    // Sample 4 is ẑ; the others ±3σ along the axes (eigenvectors of a diagonal S).
    EXPECT_NEAR(area.samples()[4].phi, 0.3, 1e-15);
    EXPECT_NEAR(area.samples()[4].beta, -0.2, 1e-15);
    double max_dphi = 0, max_dbeta = 0;
    for (const auto& s : area.samples()) {
        max_dphi = std::max(max_dphi, std::abs(s.phi - 0.3));
        max_dbeta = std::max(max_dbeta, std::abs(s.beta + 0.2));
    }
    EXPECT_NEAR(max_dphi, 0.06, 1e-12);
    EXPECT_NEAR(max_dbeta, 0.03, 1e-12);

    // 3σ ≥ 90°: no restriction.
    p.S(0, 0) = std::pow(M_PI / 6, 2);
    const PredictedSearchArea whole(p, 3.0, DEG2RAD(1.5));
    EXPECT_TRUE(whole.wholeSphere());
    EXPECT_TRUE(whole.contains(Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitZ()));

    // Bad predictions and parameters.
    TPrediction bad = p;
    bad.S(0, 1) = 1e-3;
    EXPECT_THROW(PredictedSearchArea(bad, 3.0, 0.02), std::invalid_argument);
    bad = p;
    bad.S(1, 1) = -1e-4;
    EXPECT_THROW(PredictedSearchArea(bad, 3.0, 0.02), std::invalid_argument);
    bad = p;
    bad.z.phi = NAN;
    EXPECT_THROW(PredictedSearchArea(bad, 3.0, 0.02), std::invalid_argument);
    EXPECT_THROW(PredictedSearchArea(p, -1.0, 0.02), std::invalid_argument);
    EXPECT_THROW(PredictedSearchArea(p, 3.0, 0.0), std::invalid_argument);
}

// ------------------------------------------------------------------------------------------
// ViewFeatureMatcher

// Points 0..59 of the scene each have a twin: current points 60..119 carry their descriptors
// (and view points 60..119 fresh ones, so they match nothing). Unrestricted, Lowe's ratio test
// rejects every twinned point; restricted to the predicted area (σ 3° and 1.5°) 90 % are
// matched, all correctly. Matches use each current point once and never pair opposite Laplacian
// signs.
TEST(ViewFeatureMatcher, PredictedAreaResolvesRepeatedDescriptors)
{
    CRandomGenerator rng(7);
    size_t restricted_total = 0;
    for (int trial = 0; trial < 20; trial++) {
        TSynthetic s = synthetic(rng, 120, 0, 0.5);
        for (size_t k = 60; k < 120; k++) {
            s.current.descriptors[k] = noisy(s.current.descriptors[k - 60], 0.001, rng);
            s.current.laplacian_signs[k] = s.current.laplacian_signs[k - 60];
            s.view.descriptors[k] = randomDescriptor(rng);
        }
        TPrediction p;
        p.z = {s.truth.phi + DEG2RAD(2.0), s.truth.beta - DEG2RAD(1.0)};
        p.S << std::pow(DEG2RAD(3.0), 2), 0, 0, std::pow(DEG2RAD(1.5), 2);
        ViewFeatureMatcher::TOptions opt;
        const auto restricted = ViewFeatureMatcher(opt).match(s.current, s.view, p);
        opt.restrict_search_area = false;
        const auto unrestricted = ViewFeatureMatcher(opt).match(s.current, s.view, p);

        std::set<uint32_t> used;
        for (const auto& m : restricted.matches) {
            EXPECT_TRUE(used.insert(m.current).second);
            EXPECT_EQ(s.current.laplacian_signs[m.current], s.view.laplacian_signs[m.view]);
            EXPECT_EQ(m.current, m.view) << trial;
        }
        restricted_total += restricted.matches.size();
        EXPECT_GE(restricted.matches.size(), 40u) << trial;
        EXPECT_TRUE(unrestricted.matches.empty()) << trial;
        EXPECT_LT(restricted.candidates_compared, unrestricted.candidates_compared / 4);
        EXPECT_TRUE(
            std::is_sorted(restricted.matches.begin(), restricted.matches.end(),
                           [](const auto& a, const auto& b) { return a.current < b.current; }));
    }
    // Measured 1074 of 1200: a twin falls inside the same area for 10 % of the points.
    EXPECT_GT(restricted_total, 20u * 50u);
}

TEST(ViewFeatureMatcher, DistanceAndMutualConsistency)
{
    CRandomGenerator rng(8);
    TSynthetic s = synthetic(rng, 40, 0, 0.0);
    TPrediction p;
    p.z = s.truth;
    p.S = Eigen::Matrix2d::Identity() * 1e-6;
    ViewFeatureMatcher::TOptions opt;
    opt.restrict_search_area = false;
    // Point 0 far from its match in descriptor space: no match.
    s.current.descriptors[0] = randomDescriptor(rng);
    // View point 2 is a copy of view point 1: both want current point 1, the nearer keeps it.
    s.view.descriptors[2] = noisy(s.view.descriptors[1], 0.001, rng);
    s.view.laplacian_signs[2] = s.view.laplacian_signs[1];
    const auto r = ViewFeatureMatcher(opt).match(s.current, s.view, p);
    size_t claims_of_1 = 0;
    for (const auto& m : r.matches) {
        EXPECT_NE(m.current, 0u);
        EXPECT_LE(m.distance, opt.max_descriptor_distance);
        claims_of_1 += m.current == 1;
        if (m.current == 1) {
            const float d1 = float(mrpt_vslam::core::USurfDescriptor::distance(
                s.current.descriptors[1], s.view.descriptors[1]));
            const float d2 = float(mrpt_vslam::core::USurfDescriptor::distance(
                s.current.descriptors[1], s.view.descriptors[2]));
            EXPECT_EQ(m.view, d1 <= d2 ? 1u : 2u);
        }
    }
    // Two view points on one current point fail the ratio test of neither (they are not each
    // other's candidates): the current point goes to the nearer one.
    EXPECT_EQ(claims_of_1, 1u);
    EXPECT_EQ(r.matches.size(), 38u);

    // Inconsistent features.
    TViewFeatures bad = s.current;
    bad.laplacian_signs.pop_back();
    EXPECT_THROW(ViewFeatureMatcher(opt).match(bad, s.view, p), std::invalid_argument);
}

TEST(ViewFeatureMatcher, OptionsFromIniAndValidation)
{
    mrpt::config::CConfigFileMemory ini;
    ini.write("M", "search_sigmas", 2.5);
    ini.write("M", "area_tolerance_deg", 2.0);
    ini.write("M", "max_ratio", 0.7);
    ini.write("M", "max_descriptor_distance", 0.5);
    ini.write("M", "restrict_search_area", false);
    ViewFeatureMatcher::TOptions o;
    o.loadFromConfigFile(ini, "M");
    EXPECT_DOUBLE_EQ(o.search_sigmas, 2.5);
    EXPECT_NEAR(o.area_tolerance, DEG2RAD(2.0), 1e-15);
    EXPECT_DOUBLE_EQ(o.max_ratio, 0.7);
    EXPECT_DOUBLE_EQ(o.max_descriptor_distance, 0.5);
    EXPECT_FALSE(o.restrict_search_area);
    ViewFeatureMatcher::TOptions back;
    back.loadFromConfigFile(savedAndReparsed(o, "M"), "M");
    EXPECT_NEAR(back.area_tolerance, o.area_tolerance, 1e-12);
    EXPECT_EQ(back.restrict_search_area, o.restrict_search_area);

    for (const auto& [key, value] :
         std::vector<std::pair<std::string, double>>{{"search_sigmas", -1},
                                                     {"area_tolerance_deg", 0},
                                                     {"max_ratio", 1.5},
                                                     {"max_descriptor_distance", 0}}) {
        mrpt::config::CConfigFileMemory b;
        b.write("M", key, value);
        try {
            ViewFeatureMatcher::TOptions t;
            t.loadFromConfigFile(b, "M");
            ADD_FAILURE() << key << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    }
}

// ------------------------------------------------------------------------------------------
// OmniViewObserver

// 150 matches, 0.5 px of noise, 20 % wrong matches, 200 scenes, no floors: (φ, β) within a few
// tenths of a degree and eᵀ R⁻¹ e averaging 2 (the mean of χ²₂).
TEST(OmniViewObserver, RecoversTheMotionWithAConsistentCovariance)
{
    CRandomGenerator rng(9);
    OmniViewObserver::TOptions opt;
    opt.matching.restrict_search_area = false;
    opt.min_sigma_phi = opt.min_sigma_beta = 0;
    const OmniViewObserver observer(opt);
    double sum_nees = 0, sum2_phi = 0, sum2_beta = 0;
    int n = 0, failures = 0, wrong_kept = 0;
    for (int trial = 0; trial < 200; trial++) {
        const TSynthetic s = synthetic(rng, 150, 30, 0.5);
        TPrediction p;
        p.z = s.truth;
        const auto o = observer.observe(s.current, s.view, p, rng);
        if (!o) {
            failures++;
            continue;
        }
        const Eigen::Vector2d e(wrapped(o->z.phi - s.truth.phi), wrapped(o->z.beta - s.truth.beta));
        sum_nees += e.dot(o->R.inverse() * e);
        sum2_phi += e(0) * e(0);
        sum2_beta += e(1) * e(1);
        n++;
        EXPECT_EQ(o->inliers, o->inlier_current.size());
        EXPECT_EQ(o->inliers, o->inlier_view.size());
        for (size_t i = 0; i < o->inliers; i++)
            wrong_kept += o->inlier_current[i] != o->inlier_view[i];
        EXPECT_GE(o->matches, 140u);
        EXPECT_GT(o->rms_residual, 0);
    }
    EXPECT_EQ(failures, 0);
    const double mean_nees = sum_nees / n;
    EXPECT_GT(mean_nees, 1.5);
    EXPECT_LT(mean_nees, 3.0);
    EXPECT_LT(mrpt::RAD2DEG(std::sqrt(sum2_phi / n)), 0.45);
    EXPECT_LT(mrpt::RAD2DEG(std::sqrt(sum2_beta / n)), 0.1);
    // Swapped pairs that happen to lie near their epipolar curves cannot be told from inliers;
    // 175 of the 6000 wrong matches (measured) stay.
    EXPECT_LT(wrong_kept, 300);
}

TEST(OmniViewObserver, FloorsTooFewMatchesAndRefine)
{
    CRandomGenerator rng(10);
    const TSynthetic s = synthetic(rng, 100, 0, 0.0);
    TPrediction p;
    p.z = s.truth;
    p.S = Eigen::Matrix2d::Identity() * std::pow(DEG2RAD(2.0), 2);
    const OmniViewObserver observer;
    const auto o = observer.observe(s.current, s.view, p, rng);
    ASSERT_TRUE(o.has_value());
    // Noiseless: exact, and R is the floors.
    EXPECT_NEAR(wrapped(o->z.phi - s.truth.phi), 0, 1e-7);
    EXPECT_NEAR(wrapped(o->z.beta - s.truth.beta), 0, 1e-7);
    EXPECT_NEAR(o->R(0, 0), std::pow(observer.options().min_sigma_phi, 2), 1e-15);
    EXPECT_NEAR(o->R(1, 1), std::pow(observer.options().min_sigma_beta, 2), 1e-15);
    EXPECT_EQ(o->inliers, 100u);
    EXPECT_LT(o->candidates_compared, 100u * 100u / 2);

    // Refinement from a perturbed start converges back.
    std::vector<size_t> all(100);
    for (size_t k = 0; k < all.size(); k++) all[k] = k;
    Eigen::Matrix3Xd rays_v = s.current.rays, rays_l = s.view.rays;
    const auto ls = OmniViewObserver::refine(
        {s.truth.phi + DEG2RAD(1.0), s.truth.beta - DEG2RAD(0.5)}, rays_v, rays_l, all);
    ASSERT_TRUE(ls.has_value());
    EXPECT_NEAR(wrapped(ls->z.phi - s.truth.phi), 0, 1e-8);
    EXPECT_NEAR(wrapped(ls->z.beta - s.truth.beta), 0, 1e-8);
    EXPECT_FALSE(OmniViewObserver::refine(s.truth, rays_v, rays_l, {0, 1}).has_value());

    // Fewer matches than min_inliers: no observation.
    TSynthetic few = synthetic(rng, 6, 0, 0.0);
    EXPECT_FALSE(observer.observe(few.current, few.view, p, rng).has_value());
}

TEST(OmniViewObserver, OptionsFromIniAndValidation)
{
    mrpt::config::CConfigFileMemory ini;
    ini.write("Obs", "min_sigma_phi_deg", 0.7);
    ini.write("Obs", "min_sigma_beta_deg", 0.3);
    ini.write("Obs", "inlier_threshold_deg", 0.8);
    ini.write("Obs", "max_ratio", 0.75);
    OmniViewObserver::TOptions o;
    o.loadFromConfigFile(ini, "Obs");
    EXPECT_NEAR(o.min_sigma_phi, DEG2RAD(0.7), 1e-15);
    EXPECT_NEAR(o.min_sigma_beta, DEG2RAD(0.3), 1e-15);
    EXPECT_NEAR(o.ransac.inlier_threshold, DEG2RAD(0.8), 1e-15);
    EXPECT_DOUBLE_EQ(o.matching.max_ratio, 0.75);
    OmniViewObserver::TOptions back;
    back.loadFromConfigFile(savedAndReparsed(o, "Obs"), "Obs");
    EXPECT_NEAR(back.min_sigma_beta, o.min_sigma_beta, 1e-12);
    EXPECT_NEAR(back.ransac.inlier_threshold, o.ransac.inlier_threshold, 1e-12);

    for (const auto& [key, value] :
         std::vector<std::pair<std::string, double>>{{"min_sigma_phi_deg", -1},
                                                     {"min_sigma_beta_deg", 95},
                                                     {"min_inliers", 2},
                                                     {"search_sigmas", -2}}) {
        mrpt::config::CConfigFileMemory b;
        b.write("Obs", key, value);
        try {
            OmniViewObserver::TOptions t;
            t.loadFromConfigFile(b, "Obs");
            ADD_FAILURE() << key << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    }
}
