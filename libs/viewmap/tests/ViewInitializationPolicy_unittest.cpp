#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/viewmap/ViewInitializationPolicy.h>

#include <cmath>
#include <stdexcept>
#include <vector>

using mrpt::math::TPose2D;
using namespace mrpt_vslam::viewmap;
using TReason = TViewDecision::TReason;

namespace {

/** A crafted run: the robot starts on a view at the origin and drives along x at 0.15 m per
 *  step, observing that view each step with the true (φ, β) and a noise that grows as the
 *  consistent points fall from 200 to 0 over 20 steps (R ∝ 1/inliers); the consistent points
 *  are a shrinking sector of a ring of 200 rays. Returns the first step at which the policy
 *  starts a view (−1: never within 25 steps) and its decision. */
struct TCraftedRun {
    int step = -1;
    TViewDecision decision;
    double sqrt_trace = 0;  ///< √trace P_vv when the view is started
};

TCraftedRun runAway(ViewInitializationPolicy& policy)
{
    mrpt::random::CRandomGenerator rng(1);
    const Eigen::Matrix3d P0 = Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal();
    ViewMapEKF ekf(TPose2D(0, 0, 0), P0);
    TViewPolicyInputs in;
    in.ekf = &ekf;
    const auto first = policy.decide(in, rng);
    EXPECT_TRUE(first.add);
    EXPECT_EQ(first.reason, TReason::FirstView);
    ekf.addView();

    TViewFeatures features;
    const int n = 200;
    features.rays.resize(3, n);
    for (int k = 0; k < n; k++) {
        const double a = 2 * M_PI * (k + 0.5) / n, e = mrpt::DEG2RAD(20.0 + (k % 5) * 10);
        features.rays.col(k) << std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e);
    }
    in.features = &features;
    const Eigen::Matrix3d Q =
        Eigen::Vector3d(std::pow(0.01, 2), std::pow(0.005, 2), std::pow(mrpt::DEG2RAD(0.5), 2))
            .asDiagonal();
    const double sigma0 = mrpt::DEG2RAD(0.5);
    for (int step = 1; step <= 25; step++) {
        in.P_vv_previous = ekf.robotCovariance();
        ekf.predict(TPose2D(0.15, 0, 0), Q);
        in.P_vv_predicted = ekf.robotCovariance();
        const int inliers = std::max(0, n - 10 * step);
        in.consistent.assign(n, false);
        for (int k = 0; k < inliers; k++) in.consistent[size_t(k)] = true;
        in.observed.clear();
        if (inliers >= 8) {
            const Eigen::Matrix2d R =
                Eigen::Matrix2d::Identity() * sigma0 * sigma0 * double(n) / inliers;
            const auto h = predictViewObservation(TPose2D(0.15 * step, 0, 0), TPose2D(0, 0, 0));
            EXPECT_TRUE(ekf.update(0, h, R, 1e9).accepted);
            in.observed.push_back({0, R, size_t(inliers)});
        }
        in.nearest_view_distance = std::hypot(ekf.robotPose().x, ekf.robotPose().y);
        const auto d = policy.decide(in, rng);
        if (d.add) return {step, d, std::sqrt(ekf.robotCovariance().trace())};
    }
    return {};
}

ViewInitializationPolicy::TOptions options(ViewInitializationPolicy::TKind kind)
{
    ViewInitializationPolicy::TOptions o;
    o.policy = kind;
    o.min_view_spacing = 0.4;
    o.max_view_distance = 10;
    o.min_inliers = 20;
    return o;
}

}  // namespace

TEST(ViewInitializationPolicy, TraditionalFollowsInliersAndDistance)
{
    auto o = options(ViewInitializationPolicy::TKind::Traditional);
    auto few = ViewInitializationPolicy::create(o);
    const auto r = runAway(*few);
    // 200 − 10 k < 20 first at k = 19, 2.85 m from the view.
    EXPECT_EQ(r.step, 19);
    EXPECT_EQ(r.decision.reason, TReason::FewInliers);

    o.max_view_distance = 1.0;  // passed at step 7 (1.05 m)
    auto far = ViewInitializationPolicy::create(o);
    const auto f = runAway(*far);
    EXPECT_EQ(f.step, 7);
    EXPECT_EQ(f.decision.reason, TReason::TooFar);
}

TEST(ViewInitializationPolicy, InformationStartsAViewAfterKFramesInDeficit)
{
    // Driving away from the only view, each frame gains less than the motion loses.
    auto o = options(ViewInitializationPolicy::TKind::Information);
    std::vector<int> steps;
    for (const auto& [tau, K] :
         std::vector<std::pair<double, int>>{{0.02, 3}, {0.02, 5}, {0.12, 3}}) {
        o.information_deficit = tau;
        o.deficit_frames = K;
        auto policy = ViewInitializationPolicy::create(o);
        const auto r = runAway(*policy);
        std::cout << "tau " << tau << " nats, K " << K << ": view at step " << r.step << " ("
                  << TViewDecision::reasonName(r.decision.reason) << ", balance "
                  << r.decision.information_balance << ", sure points " << r.decision.sure_points
                  << ", sqrt trace P_vv " << r.sqrt_trace << ")\n";
        ASSERT_GT(r.step, 2);  // beyond the 0.4 m spacing
        EXPECT_EQ(r.decision.reason, TReason::InformationDeficit);
        EXPECT_LT(r.decision.information_balance, -tau);
        steps.push_back(r.step);
    }
    // Every frame beyond the 0.4 m spacing (step 3 on) is in deficit by more than 0.02 nats,
    // so the view comes K frames later; a larger τ waits until the deficit grows, and every
    // run starts the view before the traditional policy's inlier threshold (step 19).
    EXPECT_EQ(steps[0], 3 + 3 - 1);
    EXPECT_EQ(steps[1], 3 + 5 - 1);
    EXPECT_GT(steps[2], steps[1]);
    EXPECT_LT(steps[2], 19);
}

TEST(ViewInitializationPolicy, CommonRulesAndOptions)
{
    mrpt::random::CRandomGenerator rng(1);
    for (const auto kind : {ViewInitializationPolicy::TKind::Traditional,
                            ViewInitializationPolicy::TKind::Information}) {
        auto policy = ViewInitializationPolicy::create(options(kind));
        ViewMapEKF ekf(TPose2D(0, 0, 0), Eigen::Matrix3d::Identity() * 1e-4);
        ekf.addView();
        TViewPolicyInputs in;
        in.ekf = &ekf;
        in.nearest_view_distance = 0.3;  // inside the spacing: never, even with no observation
        EXPECT_FALSE(policy->decide(in, rng).add);
        in.nearest_view_distance = 0.5;
        const auto d = policy->decide(in, rng);
        EXPECT_TRUE(d.add);
        EXPECT_EQ(d.reason, TReason::NoObservation);
    }

    mrpt::config::CConfigFileMemory cfg(
        "[P]\npolicy = traditional\nmin_inliers = 12\nmax_view_distance = 2.5\n"
        "information_deficit = 0.07\ndeficit_frames = 4\nmax_points = 50\n");
    ViewInitializationPolicy::TOptions o;
    o.loadFromConfigFile(cfg, "P");
    EXPECT_EQ(o.policy, ViewInitializationPolicy::TKind::Traditional);
    EXPECT_EQ(o.min_inliers, 12);
    EXPECT_DOUBLE_EQ(o.max_view_distance, 2.5);
    EXPECT_DOUBLE_EQ(o.information_deficit, 0.07);
    EXPECT_EQ(o.deficit_frames, 4);
    EXPECT_EQ(o.existence.max_points, 50);
    for (const char* bad : {"[P]\npolicy = sometimes\n", "[P]\ninformation_deficit = -0.1\n",
                            "[P]\ndeficit_frames = 0\n", "[P]\nmax_view_distance = 0.2\n",
                            "[P]\nmin_sure_points = -1\n"}) {
        mrpt::config::CConfigFileMemory c(bad);
        ViewInitializationPolicy::TOptions b;
        try {
            b.loadFromConfigFile(c, "P");
            ADD_FAILURE() << bad;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find("[P]"), std::string::npos) << e.what();
        }
    }
}
