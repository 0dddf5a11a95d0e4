// The omni front-end of the view SLAM (Valiente et al. 2015) on images rendered from the shipped
// omni-views world: feature extraction, matching restricted to the predicted area and the
// observation (φ, β) with its noise R, on pairs of poses 0.3-1.5 m apart with unrelated headings.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/sim/OmniViewsScenario.h>
#include <mrpt_vslam/viewmap/OmniFeatureExtractor.h>
#include <mrpt_vslam/viewmap/OmniViewObserver.h>

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

using mrpt::DEG2RAD;
using mrpt::RAD2DEG;
using mrpt::math::TPose2D;
using mrpt_vslam::viewmap::OmniFeatureExtractor;
using mrpt_vslam::viewmap::OmniViewObserver;
using mrpt_vslam::viewmap::TPrediction;
using mrpt_vslam::viewmap::TViewFeatures;
using mrpt_vslam::viewmap::TViewObservation;

namespace {

/// The shipped scenario with its world built and the pixel noise seeded.
struct TWorld {
    mrpt_vslam::sim::OmniViewsScenario scenario;
    mrpt_vslam::sim::TOfficeModel model;
    std::vector<TPose2D> path;

    TWorld()
    {
        scenario.loadConfig(mrpt::config::CConfigFile(
            MRPT_VSLAM_SOURCE_DIR "/share/mrpt-vslam/config/vslam-sim/omni-views.ini"));
        model = scenario.world.build(scenario.textures);
        path = scenario.trajectory.generate(scenario.trajectory.frames);
        scenario.renderer.reset(2004);
    }

    mrpt::img::CImage render(const TPose2D& robot)
    {
        return scenario.renderer.render(
            model.scene,
            mrpt::poses::CPose3D(mrpt::poses::CPose2D(robot)) + scenario.camera_on_robot);
    }
};

TWorld& world()
{
    static TWorld w;
    return w;
}

OmniFeatureExtractor extractor()
{
    // Camera frame = robot frame (the shipped [CameraOnRobot] has no rotation).
    return OmniFeatureExtractor(world().scenario.renderer.camera(), Eigen::Matrix3d::Identity(),
                                {});
}

double wrapped(double a) { return mrpt::math::wrapToPi(a); }

struct TPairResult {
    double distance = 0;
    std::optional<OmniViewObserver::TObservation> restricted, unrestricted;
    TViewObservation truth;
};

/** `n` pairs of path positions 0.3-1.5 m apart (free space), headings drawn at random; the
 *  prediction is off the truth by (+1σ, −1σ) with σ = 3° in φ and 1.5° in β. */
std::vector<TPairResult> observePairs(int n)
{
    TWorld& w = world();
    const OmniFeatureExtractor fx = extractor();
    OmniViewObserver::TOptions opt;
    const OmniViewObserver restricted(opt);
    opt.matching.restrict_search_area = false;
    const OmniViewObserver unrestricted(opt);
    mrpt::random::CRandomGenerator rng(31);
    std::vector<TPairResult> results;
    for (int p = 0; p < n; p++) {
        size_t i = 0, j = 0;
        double d = 0;
        do {
            i = rng.drawUniform32bit() % w.path.size();
            j = rng.drawUniform32bit() % w.path.size();
            d = std::hypot(w.path[i].x - w.path[j].x, w.path[i].y - w.path[j].y);
        } while (d < 0.3 || d > 1.5);
        TPose2D robot = w.path[i], view = w.path[j];
        robot.phi = rng.drawUniform(-M_PI, M_PI);
        view.phi = rng.drawUniform(-M_PI, M_PI);
        const TViewFeatures current = fx.extract(w.render(robot)),
                            stored = fx.extract(w.render(view));
        TPairResult r;
        r.distance = d;
        r.truth = mrpt_vslam::viewmap::predictViewObservation(robot, view);
        TPrediction prediction;
        prediction.z = {r.truth.phi + DEG2RAD(3.0), r.truth.beta - DEG2RAD(1.5)};
        prediction.S << std::pow(DEG2RAD(3.0), 2), 0, 0, std::pow(DEG2RAD(1.5), 2);
        mrpt::random::CRandomGenerator ransac_rng_r(p), ransac_rng_u(p);
        r.restricted = restricted.observe(current, stored, prediction, ransac_rng_r);
        r.unrestricted = unrestricted.observe(current, stored, prediction, ransac_rng_u);
        results.push_back(r);
    }
    return results;
}

double nees(const OmniViewObserver::TObservation& o, const TViewObservation& truth)
{
    const Eigen::Vector2d e(wrapped(o.z.phi - truth.phi), wrapped(o.z.beta - truth.beta));
    return e.dot(o.R.inverse() * e);
}

}  // namespace

// 16 pairs. Measured (restricted): errors at most 0.66° in φ and 0.23° in β (RMS 0.37° and
// 0.11°); the least-squares σ is below the floors on every pair, so R is the floors
// (0.5°, 0.2°) and the mean NEES 0.78. Restricted: 1739 inliers of 2202 matches (0.79) with 14 %
// of the descriptor comparisons; unrestricted: 1463 of 1989 (0.74).
TEST(ViewFrontEnd, RenderedPairsGiveTheRelativePose)
{
    const auto results = observePairs(16);
    size_t inliers_r = 0, matches_r = 0, inliers_u = 0, matches_u = 0, compared_r = 0,
           compared_u = 0;
    double sum2_phi = 0, sum2_beta = 0, sum_nees = 0;
    int n = 0;
    for (size_t p = 0; p < results.size(); p++) {
        const auto& r = results[p];
        ASSERT_TRUE(r.restricted.has_value()) << p;
        const auto& o = *r.restricted;
        const double e_phi = RAD2DEG(wrapped(o.z.phi - r.truth.phi));
        const double e_beta = RAD2DEG(wrapped(o.z.beta - r.truth.beta));
        std::printf(
            "pair %2zu d %.2f m: restricted %3zu/%3zu inliers, err %+.2f %+.2f deg, "
            "sigma %.2f %.2f deg, NEES %.2f",
            p, r.distance, o.inliers, o.matches, e_phi, e_beta, RAD2DEG(std::sqrt(o.R(0, 0))),
            RAD2DEG(std::sqrt(o.R(1, 1))), nees(o, r.truth));
        if (r.unrestricted) {
            std::printf(" | unrestricted %3zu/%3zu, err %+.2f %+.2f deg", r.unrestricted->inliers,
                        r.unrestricted->matches,
                        RAD2DEG(wrapped(r.unrestricted->z.phi - r.truth.phi)),
                        RAD2DEG(wrapped(r.unrestricted->z.beta - r.truth.beta)));
            inliers_u += r.unrestricted->inliers;
            matches_u += r.unrestricted->matches;
            compared_u += r.unrestricted->candidates_compared;
        }
        std::printf("\n");
        EXPECT_LT(std::abs(e_phi), 1.5) << p;
        EXPECT_LT(std::abs(e_beta), 0.5) << p;
        EXPECT_GE(o.inliers, 40u) << p;
        sum2_phi += e_phi * e_phi;
        sum2_beta += e_beta * e_beta;
        sum_nees += nees(o, r.truth);
        n++;
        inliers_r += o.inliers;
        matches_r += o.matches;
        compared_r += o.candidates_compared;
    }
    const double ratio_r = double(inliers_r) / matches_r, ratio_u = double(inliers_u) / matches_u;
    std::printf(
        "restricted: %zu inliers of %zu matches (%.3f), %zu comparisons; unrestricted: "
        "%zu of %zu (%.3f), %zu comparisons; RMS %.2f %.2f deg, mean NEES %.2f\n",
        inliers_r, matches_r, ratio_r, compared_r, inliers_u, matches_u, ratio_u, compared_u,
        std::sqrt(sum2_phi / n), std::sqrt(sum2_beta / n), sum_nees / n);
    EXPECT_LT(std::sqrt(sum2_phi / n), 0.8);
    EXPECT_LT(std::sqrt(sum2_beta / n), 0.25);
    EXPECT_GT(sum_nees / n, 0.5);
    EXPECT_LT(sum_nees / n, 3.0);
    EXPECT_GE(inliers_r, inliers_u);
    EXPECT_GT(ratio_r, ratio_u);
    EXPECT_LT(compared_r, compared_u / 4);
}

TEST(ViewFrontEnd, ExtractionIsDeterministicAndChecksTheImageSize)
{
    TWorld& w = world();
    const OmniFeatureExtractor fx = extractor();
    const mrpt::img::CImage image = w.render(w.path[100]);
    const TViewFeatures a = fx.extract(image), b = fx.extract(image);
    // Measured: the 400 strongest of about 650 fast-Hessian points.
    EXPECT_EQ(a.size(), 400u);
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(a.rays, b.rays);
    EXPECT_EQ(a.descriptors, b.descriptors);
    EXPECT_EQ(a.laplacian_signs, b.laplacian_signs);

    mrpt::img::CImage small;
    image.scaleImage(small, 320, 240);
    EXPECT_THROW(fx.extract(small), std::invalid_argument);
}
