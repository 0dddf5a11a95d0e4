#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/UnifiedSphereCamera.h>
#include <mrpt_vslam/test/PlanarScene.h>
#include <mrpt_vslam/viewmap/PlanarEssentialRansac.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

using mrpt::random::CRandomGenerator;
using mrpt_vslam::core::UnifiedSphereCamera;
using mrpt_vslam::viewmap::PlanarEssentialMatrix;
using mrpt_vslam::viewmap::PlanarEssentialRansac;
using mrpt_vslam::viewmap::predictViewObservation;
using mrpt_vslam::viewmap::TViewObservation;
using mrpt_vslam::viewmap::test::angleError;
using mrpt_vslam::viewmap::test::measuredRay;
using mrpt_vslam::viewmap::test::randomScene;
using mrpt_vslam::viewmap::test::rayFrom;
using mrpt_vslam::viewmap::test::raysFrom;
using mrpt_vslam::viewmap::test::TPlanarScene;
using mrpt_vslam::viewmap::test::TSceneOptions;

namespace {

/// Matches of a scene as measured by the default 640 × 480 omni camera with σ px of noise;
/// the last `outliers` matches pair a robot ray with the view ray of another point.
struct TMeasuredMatches {
    Eigen::Matrix3Xd rays_v, rays_l;
    std::vector<bool> is_outlier;
};

TMeasuredMatches measure(const TPlanarScene& scene, size_t outliers, double sigma_px,
                         CRandomGenerator& rng)
{
    const UnifiedSphereCamera camera;
    const size_t n = scene.points.size();
    TMeasuredMatches m{Eigen::Matrix3Xd(3, Eigen::Index(n)), Eigen::Matrix3Xd(3, Eigen::Index(n)),
                       std::vector<bool>(n, false)};
    for (size_t k = 0; k < n; k++) {
        const bool outlier = k >= n - outliers;
        // A wrong match: a point half the scene away (different k, different direction).
        const auto& p_l = outlier ? scene.points[(k + n / 2) % n] : scene.points[k];
        const auto rv = measuredRay(camera, rayFrom(scene.robot, scene.points[k]), sigma_px, rng);
        const auto rl = measuredRay(camera, rayFrom(scene.view, p_l), sigma_px, rng);
        // Every scene point lies inside the image (elevation ≤ 25° < 30° of the camera).
        EXPECT_TRUE(rv && rl);
        if (!rv || !rl) continue;
        m.rays_v.col(Eigen::Index(k)) = *rv;
        m.rays_l.col(Eigen::Index(k)) = *rl;
        m.is_outlier[k] = outlier;
    }
    return m;
}

/// RMS and largest errors [deg] over a set of trials.
struct TErrors {
    double sum2_phi = 0, max_phi = 0, sum2_beta = 0, max_beta = 0;
    int count = 0;

    void add(const TViewObservation& z, const TViewObservation& truth)
    {
        const double e_phi = mrpt::RAD2DEG(std::abs(angleError(z.phi, truth.phi)));
        const double e_beta = mrpt::RAD2DEG(std::abs(angleError(z.beta, truth.beta)));
        sum2_phi += e_phi * e_phi;
        sum2_beta += e_beta * e_beta;
        max_phi = std::max(max_phi, e_phi);
        max_beta = std::max(max_beta, e_beta);
        count++;
    }
    double rmsPhi() const { return std::sqrt(sum2_phi / count); }
    double rmsBeta() const { return std::sqrt(sum2_beta / count); }
};

/// RANSAC on random scenes, and for reference the linear fit on the true inliers alone.
struct TTrialStats {
    TErrors ransac, oracle;
    int failures = 0;
    double outliers_flagged = 1;  ///< smallest share over the trials
    double inliers_kept = 1;      ///< smallest share over the trials
};

TTrialStats runTrials(int trials, size_t n, double outlier_ratio, double sigma_px, unsigned seed)
{
    CRandomGenerator rng(seed);
    TSceneOptions opt;
    opt.points = n;
    const PlanarEssentialRansac ransac;
    const double tau = ransac.options().inlier_threshold;
    const auto outliers = size_t(std::lround(outlier_ratio * n));
    TTrialStats s;
    for (int t = 0; t < trials; t++) {
        const auto scene = randomScene(rng, opt);
        const auto m = measure(scene, outliers, sigma_px, rng);
        const auto truth = predictViewObservation(scene.robot, scene.view);
        std::vector<size_t> true_inliers(n - outliers);
        std::iota(true_inliers.begin(), true_inliers.end(), size_t(0));
        const auto oracle = PlanarEssentialMatrix::fit(m.rays_v, m.rays_l, true_inliers);
        const auto oracle_z =
            oracle ? oracle->motion(m.rays_v, m.rays_l, true_inliers) : std::nullopt;
        if (!oracle_z) {
            ADD_FAILURE() << "no fit on the true inliers";
            continue;
        }
        s.oracle.add(*oracle_z, truth);

        const auto result = ransac.estimate(m.rays_v, m.rays_l, rng);
        if (!result) {
            s.failures++;
            continue;
        }
        s.ransac.add(result->observation, truth);
        EXPECT_EQ(result->inlier_count,
                  size_t(std::count(result->inliers.begin(), result->inliers.end(), true)));
        // Outliers that contradict the true geometry (residual > 2τ) must be flagged; the
        // others cannot be told from inliers by geometry.
        const auto true_E = PlanarEssentialMatrix::fromMotion(truth.phi, truth.beta);
        size_t detectable = 0, flagged = 0, kept = 0;
        for (size_t k = 0; k < n; k++) {
            const auto col = Eigen::Index(k);
            if (m.is_outlier[k] &&
                true_E.residual(m.rays_v.col(col), m.rays_l.col(col)) > 2 * tau) {
                detectable++;
                flagged += !result->inliers[k];
            }
            kept += !m.is_outlier[k] && result->inliers[k];
        }
        if (detectable > 0) {
            s.outliers_flagged = std::min(s.outliers_flagged, double(flagged) / detectable);
        }
        s.inliers_kept = std::min(s.inliers_kept, double(kept) / double(n - outliers));
    }
    return s;
}

}  // namespace

TEST(PlanarEssentialRansac, NoiselessMatchesAreSolvedExactly)
{
    CRandomGenerator rng(1);
    const PlanarEssentialRansac ransac;
    for (int trial = 0; trial < 50; trial++) {
        const auto scene = randomScene(rng);
        const auto rays_v = raysFrom(scene.robot, scene.points);
        const auto rays_l = raysFrom(scene.view, scene.points);
        const auto result = ransac.estimate(rays_v, rays_l, rng);
        ASSERT_TRUE(result.has_value());
        const auto truth = predictViewObservation(scene.robot, scene.view);
        EXPECT_NEAR(angleError(result->observation.phi, truth.phi), 0, 1e-9);
        EXPECT_NEAR(angleError(result->observation.beta, truth.beta), 0, 1e-9);
        EXPECT_EQ(result->inlier_count, scene.points.size());
        EXPECT_LT(result->rms_residual, 1e-12);
        EXPECT_GT(result->median_parallax, ransac.options().min_parallax);
        // All inliers: one sample is enough.
        EXPECT_EQ(result->iterations, 1u);
    }
}

// 100 matches on the 640 × 480 omni camera with 1 px of noise (about 0.4-0.6° per ray), over
// 200 scenes with baselines of 0.3-2 m: measured RMS (max) errors 0.99° (4.5°) in φ and
// 0.17° (0.53°) in β, as good as the fit on all matches (0.93° in φ).
TEST(PlanarEssentialRansac, PixelNoiseGivesDegreeLevelErrors)
{
    const auto s = runTrials(200, 100, 0.0, 1.0, 10);
    EXPECT_EQ(s.failures, 0);
    EXPECT_LT(s.ransac.rmsPhi(), 1.2);
    EXPECT_LT(s.ransac.max_phi, 6.0);
    EXPECT_LT(s.ransac.rmsBeta(), 0.3);
    EXPECT_LT(s.ransac.max_beta, 1.0);
    EXPECT_LT(s.ransac.rmsPhi(), 1.2 * s.oracle.rmsPhi());
    EXPECT_LT(s.ransac.rmsBeta(), 1.2 * s.oracle.rmsBeta());
    EXPECT_GT(s.inliers_kept, 0.9);
}

// 150 matches, 1 px of noise, 30 % and 50 % wrong matches, 100 scenes each. Measured RMS (max)
// errors in φ: 1.23° (4.4°) and 1.87° (6.2°), against 0.86° and 1.12° for the fit on the true
// inliers alone; β: 0.20° (0.55°) in both cases, like that fit. Outliers that contradict the
// true geometry: ≥ 96.9 % flagged; true inliers: ≥ 93 % kept.
TEST(PlanarEssentialRansac, OutliersAreFlaggedAndBarelyAffectTheEstimate)
{
    for (double ratio : {0.3, 0.5}) {
        const auto s = runTrials(100, 150, ratio, 1.0, 20);
        EXPECT_EQ(s.failures, 0) << ratio;
        EXPECT_LT(s.ransac.rmsPhi(), 2.0 * s.oracle.rmsPhi()) << ratio;
        EXPECT_LT(s.ransac.rmsBeta(), 1.3 * s.oracle.rmsBeta()) << ratio;
        EXPECT_LT(s.ransac.rmsPhi(), 2.5) << ratio;
        EXPECT_LT(s.ransac.max_phi, 8.0) << ratio;
        EXPECT_LT(s.ransac.rmsBeta(), 0.3) << ratio;
        EXPECT_LT(s.ransac.max_beta, 1.0) << ratio;
        EXPECT_GT(s.outliers_flagged, 0.95) << ratio;
        EXPECT_GT(s.inliers_kept, 0.9) << ratio;
    }
}

TEST(PlanarEssentialRansac, SeededGeneratorGivesReproducibleResults)
{
    CRandomGenerator scene_rng(5);
    TSceneOptions opt;
    opt.points = 120;
    const auto scene = randomScene(scene_rng, opt);
    const auto m = measure(scene, 50, 1.0, scene_rng);
    const PlanarEssentialRansac ransac;
    CRandomGenerator a(77), b(77);
    const auto ra = ransac.estimate(m.rays_v, m.rays_l, a);
    const auto rb = ransac.estimate(m.rays_v, m.rays_l, b);
    ASSERT_TRUE(ra && rb);
    EXPECT_EQ(ra->observation.phi, rb->observation.phi);
    EXPECT_EQ(ra->observation.beta, rb->observation.beta);
    EXPECT_EQ(ra->inliers, rb->inliers);
    EXPECT_EQ(ra->iterations, rb->iterations);
    EXPECT_GT(ra->iterations, 1u);
}

TEST(PlanarEssentialRansac, DegenerateInputHasNoSolution)
{
    CRandomGenerator rng(6);
    const PlanarEssentialRansac ransac;
    const auto scene = randomScene(rng);
    const Eigen::Matrix3Xd rays_v = raysFrom(scene.robot, scene.points);
    const Eigen::Matrix3Xd rays_l = raysFrom(scene.view, scene.points);
    ASSERT_TRUE(ransac.estimate(rays_v, rays_l, rng).has_value());

    // Fewer than 4 matches, and fewer than min_inliers.
    EXPECT_FALSE(ransac.estimate(rays_v.leftCols(3), rays_l.leftCols(3), rng).has_value());
    EXPECT_FALSE(ransac.estimate(rays_v.leftCols(7), rays_l.leftCols(7), rng).has_value());
    EXPECT_FALSE(ransac.estimate(Eigen::Matrix3Xd(3, 0), Eigen::Matrix3Xd(3, 0), rng).has_value());

    // The same match 50 times.
    EXPECT_FALSE(
        ransac.estimate(rays_v.col(0).replicate(1, 50), rays_l.col(0).replicate(1, 50), rng)
            .has_value());

    // Zero baseline: exact, then measured with 1 px of noise (a rotation explains all rays).
    auto still = scene;
    still.view.x = still.robot.x;
    still.view.y = still.robot.y;
    EXPECT_FALSE(
        ransac
            .estimate(raysFrom(still.robot, still.points), raysFrom(still.view, still.points), rng)
            .has_value());
    const auto noisy = measure(still, 0, 1.0, rng);
    EXPECT_FALSE(ransac.estimate(noisy.rays_v, noisy.rays_l, rng).has_value());

    // Malformed input throws.
    EXPECT_THROW(ransac.estimate(rays_v, rays_l.leftCols(10), rng), std::invalid_argument);
    Eigen::Matrix3Xd scaled = rays_l;
    scaled.col(4) *= 0.5;
    EXPECT_THROW(ransac.estimate(rays_v, scaled, rng), std::invalid_argument);
}

TEST(PlanarEssentialRansac, OptionsFromIniAndValidation)
{
    mrpt::config::CConfigFileMemory ini(
        "[VIEWS]\n"
        "inlier_threshold_deg = 0.8\n"
        "confidence = 0.999\n"
        "max_iterations = 500\n"
        "min_inliers = 12\n"
        "min_parallax_deg = 2\n");
    PlanarEssentialRansac::TOptions opts;
    opts.loadFromConfigFile(ini, "VIEWS");
    EXPECT_NEAR(opts.inlier_threshold, mrpt::DEG2RAD(0.8), 1e-15);
    EXPECT_DOUBLE_EQ(opts.confidence, 0.999);
    EXPECT_EQ(opts.max_iterations, 500);
    EXPECT_EQ(opts.min_inliers, 12);
    EXPECT_NEAR(opts.min_parallax, mrpt::DEG2RAD(2.0), 1e-15);

    mrpt::config::CConfigFileMemory saved;
    opts.saveToConfigFile(saved, "V");
    std::string text;
    saved.getContent(text);
    PlanarEssentialRansac::TOptions reread;
    reread.loadFromConfigFile(mrpt::config::CConfigFileMemory(text), "V");
    EXPECT_NEAR(reread.inlier_threshold, opts.inlier_threshold, 1e-12);
    EXPECT_EQ(reread.min_inliers, 12);
    EXPECT_NEAR(reread.min_parallax, opts.min_parallax, 1e-12);

    for (const std::string bad :
         {"inlier_threshold_deg = 0", "confidence = 1", "max_iterations = 0", "min_inliers = 3",
          "min_parallax_deg = -1"}) {
        PlanarEssentialRansac::TOptions o;
        try {
            o.loadFromConfigFile(mrpt::config::CConfigFileMemory("[V]\n" + bad + "\n"), "V");
            ADD_FAILURE() << "accepted " << bad;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(bad.substr(0, bad.find(' '))), std::string::npos)
                << e.what();
        }
    }
}
