#include <gtest/gtest.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/test/PlanarScene.h>
#include <mrpt_vslam/viewmap/PlanarEssentialMatrix.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

using mrpt_vslam::viewmap::PlanarEssentialMatrix;
using mrpt_vslam::viewmap::predictViewObservation;
using mrpt_vslam::viewmap::test::angleError;
using mrpt_vslam::viewmap::test::randomScene;
using mrpt_vslam::viewmap::test::raysFrom;
using mrpt_vslam::viewmap::test::TSceneOptions;

namespace {

std::vector<size_t> allOf(const Eigen::Matrix3Xd& rays)
{
    std::vector<size_t> idx(size_t(rays.cols()));
    std::iota(idx.begin(), idx.end(), size_t(0));
    return idx;
}

Eigen::Matrix3d skew(const Eigen::Vector3d& t)
{
    Eigen::Matrix3d S;
    S << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
    return S;
}

}  // namespace

TEST(PlanarEssentialMatrix, FromMotionIsCrossProductTimesRotation)
{
    for (double phi : {-2.5, -0.3, 0.0, 1.0, 3.0}) {
        for (double beta : {-3.0, -1.0, 0.0, 0.4, 2.2}) {
            const Eigen::Matrix3d expected =
                skew(Eigen::Vector3d(std::cos(phi), std::sin(phi), 0)) *
                Eigen::AngleAxisd(beta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
            const Eigen::Matrix3d E = PlanarEssentialMatrix::fromMotion(phi, beta).matrix();
            EXPECT_LT((E - expected.normalized()).norm(), 1e-12) << phi << " " << beta;
            const auto z = PlanarEssentialMatrix::fromMotion(phi, beta).motionUpToPi();
            EXPECT_NEAR(std::abs(angleError(z.phi, phi)), 0, 1e-12);
            EXPECT_NEAR(angleError(z.beta, beta), 0, 1e-12);
            // The opposite translation: same β, φ + π.
            const auto flipped = PlanarEssentialMatrix::fromMotion(phi + M_PI, beta);
            EXPECT_NEAR(angleError(flipped.motionUpToPi().beta, beta), 0, 1e-12);
            EXPECT_NEAR(std::abs(angleError(flipped.motionUpToPi().phi, phi)), M_PI, 1e-12);
        }
    }
}

// The (φ, β) recovered from noiseless matches equal h(x_v, x_l) of the true poses: same
// conventions in the essential matrix and the observation model, and the right φ branch.
TEST(PlanarEssentialMatrix, NoiselessScenesGiveTheObservationOfTheTruePoses)
{
    mrpt::random::CRandomGenerator rng(1);
    double worst_phi = 0, worst_beta = 0, worst_residual = 0;
    for (size_t n : {4, 5, 8, 30, 200}) {
        TSceneOptions opt;
        opt.points = n;
        opt.max_elevation = M_PI / 2;  // any direction
        for (int trial = 0; trial < 200; trial++) {
            const auto scene = randomScene(rng, opt);
            const auto rays_v = raysFrom(scene.robot, scene.points);
            const auto rays_l = raysFrom(scene.view, scene.points);
            const auto E = PlanarEssentialMatrix::fit(rays_v, rays_l);
            ASSERT_TRUE(E.has_value()) << n << " " << trial;
            const auto count = E->cheirality(rays_v, rays_l, allOf(rays_v));
            EXPECT_EQ(count.in_front + count.behind, n);  // all depths agree in sign
            const auto z = E->motion(rays_v, rays_l, allOf(rays_v));
            ASSERT_TRUE(z.has_value());
            const auto truth = predictViewObservation(scene.robot, scene.view);
            worst_phi = std::max(worst_phi, std::abs(angleError(z->phi, truth.phi)));
            worst_beta = std::max(worst_beta, std::abs(angleError(z->beta, truth.beta)));
            for (Eigen::Index k = 0; k < rays_v.cols(); k++) {
                worst_residual =
                    std::max(worst_residual, E->residual(rays_v.col(k), rays_l.col(k)));
            }
        }
    }
    EXPECT_LT(worst_phi, 1e-9);
    EXPECT_LT(worst_beta, 1e-9);
    EXPECT_LT(worst_residual, 1e-9);
}

TEST(PlanarEssentialMatrix, CheiralityPicksTheBranch)
{
    mrpt::random::CRandomGenerator rng(2);
    const auto scene = randomScene(rng);
    const auto rays_v = raysFrom(scene.robot, scene.points);
    const auto rays_l = raysFrom(scene.view, scene.points);
    const auto idx = allOf(rays_v);
    const auto truth = predictViewObservation(scene.robot, scene.view);
    for (double branch : {0.0, M_PI}) {
        const auto E = PlanarEssentialMatrix::fromMotion(truth.phi + branch, truth.beta);
        const auto count = E.cheirality(rays_v, rays_l, idx);
        EXPECT_EQ(branch == 0 ? count.in_front : count.behind, scene.points.size());
        EXPECT_EQ(branch == 0 ? count.behind : count.in_front, 0u);
        const auto z = E.motion(rays_v, rays_l, idx);
        ASSERT_TRUE(z.has_value());
        EXPECT_NEAR(angleError(z->phi, truth.phi), 0, 1e-12);
        EXPECT_NEAR(angleError(z->beta, truth.beta), 0, 1e-12);
    }
    // No match with parallax: no decision.
    const Eigen::Matrix3Xd same = rays_v;
    const auto E0 = PlanarEssentialMatrix::fromMotion(truth.phi, 0.0);
    EXPECT_FALSE(E0.motion(same, same, idx).has_value());
}

// Forward motion without rotation, p_l straight up and p_v tilted by δ out of the epipolar
// plane: both rays must turn by δ/2 about the motion axis, so the residual is δ/√2 (to first
// order; tan δ/√2 exactly, as the gradients are linearised).
TEST(PlanarEssentialMatrix, ResidualIsTheAngularDistance)
{
    for (double delta : {1e-4, 1e-3, 0.01, 0.05}) {
        const Eigen::Vector3d p_l(0, 0, 1);
        const Eigen::Vector3d p_v(0, std::sin(delta), std::cos(delta));
        for (double phi : {0.0, M_PI}) {  // the sign of E does not matter
            const auto E = PlanarEssentialMatrix::fromMotion(phi, 0);
            EXPECT_NEAR(E.residual(p_v, p_l), std::tan(delta) / std::sqrt(2.0), 1e-15);
            EXPECT_NEAR(E.residual(p_v, p_l), delta / std::sqrt(2.0), delta * delta * delta);
            EXPECT_NEAR(E.residual(p_l, p_l), 0, 1e-17);
        }
    }
}

TEST(PlanarEssentialMatrix, DegenerateInputHasNoSolution)
{
    mrpt::random::CRandomGenerator rng(3);
    TSceneOptions opt;
    opt.points = 3;
    const auto scene3 = randomScene(rng, opt);
    EXPECT_FALSE(PlanarEssentialMatrix::fit(raysFrom(scene3.robot, scene3.points),
                                            raysFrom(scene3.view, scene3.points))
                     .has_value());

    // The same ray 20 times.
    const auto scene = randomScene(rng);
    const Eigen::Matrix3Xd one_v = raysFrom(scene.robot, scene.points).col(0).replicate(1, 20);
    const Eigen::Matrix3Xd one_l = raysFrom(scene.view, scene.points).col(0).replicate(1, 20);
    EXPECT_FALSE(PlanarEssentialMatrix::fit(one_v, one_l).has_value());

    // Zero baseline, with a rotation: the null space is two-dimensional.
    auto still = scene;
    still.view.x = still.robot.x;
    still.view.y = still.robot.y;
    EXPECT_FALSE(PlanarEssentialMatrix::fit(raysFrom(still.robot, still.points),
                                            raysFrom(still.view, still.points))
                     .has_value());

    // All points at the camera height: every equation vanishes.
    auto flat = scene;
    for (auto& p : flat.points) p.z() = 0;
    EXPECT_FALSE(PlanarEssentialMatrix::fit(raysFrom(flat.robot, flat.points),
                                            raysFrom(flat.view, flat.points))
                     .has_value());

    // The intact scene is solvable (the cases above fail for their degeneracy only).
    EXPECT_TRUE(PlanarEssentialMatrix::fit(raysFrom(scene.robot, scene.points),
                                           raysFrom(scene.view, scene.points))
                    .has_value());
}

TEST(PlanarEssentialMatrix, RejectsMalformedRays)
{
    mrpt::random::CRandomGenerator rng(4);
    const auto scene = randomScene(rng);
    const Eigen::Matrix3Xd rays_v = raysFrom(scene.robot, scene.points);
    const Eigen::Matrix3Xd rays_l = raysFrom(scene.view, scene.points);
    EXPECT_THROW(PlanarEssentialMatrix::fit(rays_v, rays_l.leftCols(50)), std::invalid_argument);
    Eigen::Matrix3Xd scaled = rays_l;
    scaled.col(7) *= 2;
    EXPECT_THROW(PlanarEssentialMatrix::fit(rays_v, scaled), std::invalid_argument);
    EXPECT_THROW(PlanarEssentialMatrix::checkRays(rays_v, scaled), std::invalid_argument);
    Eigen::Matrix3Xd nan = rays_v;
    nan(2, 3) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(PlanarEssentialMatrix::fit(nan, rays_l), std::invalid_argument);
    EXPECT_THROW(PlanarEssentialMatrix::fit(rays_v, rays_l, {0, 1, 2, 100}), std::invalid_argument);
    EXPECT_NO_THROW(PlanarEssentialMatrix::checkRays(rays_v, rays_l));
}
