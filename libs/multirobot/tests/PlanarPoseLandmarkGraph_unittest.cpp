#include <gtest/gtest.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/multirobot/PlanarPoseLandmarkGraph.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using mrpt::math::TPose2D;
using mrpt_vslam::multirobot::PlanarPoseLandmarkGraph;

namespace {

/// Two robots on arcs around six points; readings of every point within 4 m and of the other
/// robot at every fifth pose. Measurements are exact plus N(0, noise²) per component.
struct TWorld {
    std::vector<std::vector<TPose2D>> poses;  ///< [robot][step]
    std::vector<Eigen::Vector2d> points;
};

TWorld makeWorld()
{
    TWorld w;
    for (int r = 0; r < 2; r++) {
        w.poses.emplace_back();
        for (int i = 0; i < 25; i++) {
            const double a = 0.12 * i + r * 1.5, radius = 3 + r;
            w.poses.back().push_back({radius * std::cos(a), radius * std::sin(a), a + M_PI / 2});
        }
    }
    for (int j = 0; j < 6; j++)
        w.points.emplace_back(2.0 * std::cos(j * 1.1), 2.0 * std::sin(j * 1.1) + 0.5);
    return w;
}

Eigen::Vector2d inFrame(const TPose2D& x, const Eigen::Vector2d& p)
{
    const double c = std::cos(x.phi), s = std::sin(x.phi);
    const Eigen::Vector2d d(p.x() - x.x, p.y() - x.y);
    return {c * d.x() + s * d.y(), -s * d.x() + c * d.y()};
}

struct TMeasurements {
    std::vector<TPose2D> odometry[2];
    struct TReading {
        int robot, step, target;  ///< target < 0: robot −target−1 at the same step
        Eigen::Vector2d z;
    };
    std::vector<TReading> readings;
};

/// `odometry_scale[r]`: robot r's odometry reports its distances and turns divided by these.
TMeasurements measure(const TWorld& w, double noise, uint32_t seed,
                      const Eigen::Vector2d (&odometry_scale)[2] = {{1, 1}, {1, 1}})
{
    std::mt19937 gen(seed);
    std::normal_distribution<double> n(0, noise);
    TMeasurements m;
    for (int r = 0; r < 2; r++)
        for (size_t i = 1; i < w.poses[r].size(); i++) {
            const TPose2D& a = w.poses[r][i - 1];
            const TPose2D& b = w.poses[r][i];
            const Eigen::Vector2d d = inFrame(a, {b.x, b.y});
            const Eigen::Vector2d& s = odometry_scale[r];
            m.odometry[r].push_back({d.x() / s[0] + n(gen), d.y() / s[0] + n(gen),
                                     mrpt::math::wrapToPi(b.phi - a.phi) / s[1] + n(gen)});
        }
    for (int r = 0; r < 2; r++)
        for (int i = 0; i < static_cast<int>(w.poses[r].size()); i++) {
            for (int j = 0; j < static_cast<int>(w.points.size()); j++) {
                const Eigen::Vector2d z = inFrame(w.poses[r][i], w.points[j]);
                if (z.norm() < 4)
                    m.readings.push_back({r, i, j, z + Eigen::Vector2d(n(gen), n(gen))});
            }
            if (i % 5 == 0) {
                const TPose2D& o = w.poses[1 - r][i];
                const Eigen::Vector2d z = inFrame(w.poses[r][i], {o.x, o.y});
                m.readings.push_back({r, i, -(2 - r), z + Eigen::Vector2d(n(gen), n(gen))});
            }
        }
    return m;
}

/// The graph of the measurements with the given values; sigma: every factor's σ. With
/// `scales`, one odometry scale variable per robot (starting at 1, prior N(1, 10²)).
PlanarPoseLandmarkGraph makeGraph(const TWorld& values, const TWorld& truth, const TMeasurements& m,
                                  double sigma, bool scales = false)
{
    PlanarPoseLandmarkGraph g;
    const size_t steps = values.poses[0].size();
    for (int r = 0; r < 2; r++)
        for (const auto& x : values.poses[r]) g.addPose(x);
    for (const auto& p : values.points) g.addPoint(p);
    const double s2 = sigma * sigma;
    for (int r = 0; r < 2; r++) {
        g.addPosePrior(r * steps, truth.poses[r][0], Eigen::Matrix3d::Identity() * 1e-6);
        if (scales) g.addOdometryScale({1, 1}, {1, 1}, Eigen::Matrix2d::Identity() * 100);
        for (size_t i = 1; i < steps; i++) {
            const Eigen::Matrix3d cov = Eigen::Matrix3d::Identity() * s2;
            if (scales)
                g.addOdometry(r * steps + i - 1, r * steps + i, m.odometry[r][i - 1], cov, r);
            else
                g.addOdometry(r * steps + i - 1, r * steps + i, m.odometry[r][i - 1], cov);
        }
    }
    for (const auto& z : m.readings) {
        const size_t pose = z.robot * steps + z.step;
        if (z.target >= 0)
            g.addPointReading(pose, z.target, z.z, Eigen::Matrix2d::Identity() * s2);
        else
            g.addPoseReading(pose, (-z.target - 1) * steps + z.step, z.z,
                             Eigen::Matrix2d::Identity() * s2);
    }
    return g;
}

TWorld perturbed(const TWorld& w, double xy, double phi, uint32_t seed)
{
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    TWorld p = w;
    for (auto& path : p.poses)
        for (size_t i = 1; i < path.size(); i++) {
            path[i].x += xy * u(gen);
            path[i].y += xy * u(gen);
            path[i].phi += phi * u(gen);
        }
    for (auto& q : p.points) q += Eigen::Vector2d(xy * u(gen), xy * u(gen));
    return p;
}

TWorld valuesOf(const PlanarPoseLandmarkGraph& g, const TWorld& shape)
{
    TWorld v = shape;
    size_t k = 0;
    for (auto& path : v.poses)
        for (auto& x : path) x = g.pose(k++);
    for (size_t j = 0; j < v.points.size(); j++) v.points[j] = g.point(j);
    return v;
}

}  // namespace

TEST(PlanarPoseLandmarkGraph, ExactMeasurementsGiveTheTruthFromAPerturbedStart)
{
    const TWorld truth = makeWorld();
    const TMeasurements m = measure(truth, 0, 1);
    auto g = makeGraph(perturbed(truth, 0.4, 0.2, 2), truth, m, 0.05);
    const auto result = g.optimize({});
    EXPECT_GT(result.initial_cost, 1e3);
    EXPECT_LT(result.final_cost, 1e-12);
    EXPECT_EQ(result.outlier_readings, 0u);
    const TWorld v = valuesOf(g, truth);
    for (int r = 0; r < 2; r++)
        for (size_t i = 0; i < truth.poses[r].size(); i++) {
            EXPECT_NEAR(v.poses[r][i].x, truth.poses[r][i].x, 1e-6);
            EXPECT_NEAR(v.poses[r][i].y, truth.poses[r][i].y, 1e-6);
            EXPECT_NEAR(mrpt::math::wrapToPi(v.poses[r][i].phi - truth.poses[r][i].phi), 0, 1e-6);
        }
    for (size_t j = 0; j < truth.points.size(); j++)
        EXPECT_LT((v.points[j] - truth.points[j]).norm(), 1e-6);
}

// Noisy measurements: the result is a minimum of the cost, checked by finite differences on
// graphs built at the shifted values (the cost alone, not the solver's Jacobians).
TEST(PlanarPoseLandmarkGraph, TheResultIsAStationaryPointAndALocalMinimumOfTheCost)
{
    const TWorld truth = makeWorld();
    const TMeasurements m = measure(truth, 0.05, 3);
    for (const double huber : {0.0, 1.0}) {
        auto g = makeGraph(perturbed(truth, 0.3, 0.1, 4), truth, m, 0.05);
        PlanarPoseLandmarkGraph::TOptions options;
        options.huber_threshold = huber;
        options.relative_tolerance = 1e-14;
        g.optimize(options);
        const TWorld best = valuesOf(g, truth);
        const double c0 = g.cost(huber);
        const double h = 1e-6;
        std::mt19937 gen(5);
        std::uniform_real_distribution<double> u(-1, 1);
        for (int trial = 0; trial < 40; trial++) {
            // one coordinate: a pose's x, y or θ, or a point's x or y
            TWorld plus = best, minus = best;
            const int r = trial % 3, i = (trial * 7) % 25, comp = (trial / 3) % 3;
            double* a = nullptr;
            double* b = nullptr;
            if (r < 2) {
                a = comp == 0   ? &plus.poses[r][i].x
                    : comp == 1 ? &plus.poses[r][i].y
                                : &plus.poses[r][i].phi;
                b = comp == 0   ? &minus.poses[r][i].x
                    : comp == 1 ? &minus.poses[r][i].y
                                : &minus.poses[r][i].phi;
            } else {
                a = &plus.points[i % 6][comp % 2];
                b = &minus.points[i % 6][comp % 2];
            }
            *a += h;
            *b -= h;
            const double gradient = (makeGraph(plus, truth, m, 0.05).cost(huber) -
                                     makeGraph(minus, truth, m, 0.05).cost(huber)) /
                                    (2 * h);
            // curvature here ≥ 1e3 per m² or rad²: 1e-2 is within 10 µm of the minimum
            EXPECT_NEAR(gradient, 0, 1e-2) << "huber " << huber << " trial " << trial;
        }
        for (int trial = 0; trial < 20; trial++)
            EXPECT_GT(
                makeGraph(perturbed(best, 0.01, 0.005, 10 + trial), truth, m, 0.05).cost(huber),
                c0);
    }
}

TEST(PlanarPoseLandmarkGraph, EstimatesTheOdometryScales)
{
    // exact measurements but odometry that overstates robot 0's distances by 1/0.9 and turns
    // by 1/0.95 and understates robot 1's (1.1, 1.05)
    const TWorld truth = makeWorld();
    const Eigen::Vector2d scale[2] = {{0.9, 0.95}, {1.1, 1.05}};
    const TMeasurements m = measure(truth, 0, 1, scale);
    auto g = makeGraph(perturbed(truth, 0.2, 0.1, 2), truth, m, 0.05, true);
    const auto result = g.optimize({});
    // only the weak prior on the scales is not met: Σ ((s − 1) / 10)² = 2.5e-4
    EXPECT_NEAR(result.final_cost, 2.5e-4, 1e-6);
    for (int r = 0; r < 2; r++) {
        EXPECT_NEAR(g.odometryScale(r)[0], scale[r][0], 1e-4) << r;
        EXPECT_NEAR(g.odometryScale(r)[1], scale[r][1], 1e-4) << r;
    }
    double worst = 0, worstUnscaled = 0;
    auto h = makeGraph(truth, truth, m, 0.05);  // the same without scale variables
    h.optimize({});
    for (size_t i = 0; i < g.poseCount(); i++) {
        const TPose2D& x = truth.poses[i / 25][i % 25];
        worst = std::max(worst, std::hypot(g.pose(i).x - x.x, g.pose(i).y - x.y));
        worstUnscaled = std::max(worstUnscaled, std::hypot(h.pose(i).x - x.x, h.pose(i).y - x.y));
    }
    EXPECT_LT(worst, 1e-4);
    EXPECT_GT(worstUnscaled, 0.02);
}

TEST(PlanarPoseLandmarkGraph, HuberBoundsTheForceOfAWrongReading)
{
    const TWorld truth = makeWorld();
    TMeasurements m = measure(truth, 0.01, 6);
    // every reading of point 0 from robot 0's pose 3 moved by 2 m: one wrong association
    size_t moved = 0;
    for (auto& z : m.readings)
        if (z.robot == 0 && z.step == 3 && z.target == 0) {
            z.z += Eigen::Vector2d(2, 0);
            moved++;
        }
    ASSERT_EQ(moved, 1u);
    double error[2];
    for (const double huber : {0.0, 3.0}) {
        auto g = makeGraph(truth, truth, m, 0.01);
        PlanarPoseLandmarkGraph::TOptions options;
        options.huber_threshold = huber;
        const auto result = g.optimize(options);
        EXPECT_EQ(result.readings, m.readings.size());
        EXPECT_EQ(result.outlier_readings, huber > 0 ? 1u : 0u);
        error[huber > 0] = (g.point(0) - truth.points[0]).norm();
    }
    EXPECT_GT(error[0], 0.05);  // least squares: the wrong reading drags the point
    EXPECT_LT(error[1], 0.02);  // Huber: about as if it were absent
}

TEST(PlanarPoseLandmarkGraph, RejectsAGraphThatDoesNotFixEveryVariable)
{
    const TWorld truth = makeWorld();
    const TMeasurements m = measure(truth, 0, 1);
    auto g = makeGraph(truth, truth, m, 0.05);
    g.addPoint({0, 0});  // never read
    EXPECT_THROW(g.optimize({}), std::invalid_argument);
    PlanarPoseLandmarkGraph h;
    h.addPose({0, 0, 0});
    EXPECT_THROW(h.optimize({}), std::invalid_argument);  // no prior
    EXPECT_THROW(h.addPosePrior(0, {0, 0, 0}, Eigen::Matrix3d::Zero()), std::invalid_argument);
}
