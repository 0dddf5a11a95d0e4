#include <gtest/gtest.h>
#include <mrpt_vslam/viewmap/ViewBearingPairing.h>

#include <vector>

using mrpt::math::TPose2D;
using mrpt_vslam::viewmap::COmniViewSLAM;
using mrpt_vslam::viewmap::ViewBearingPairing;

namespace {

/// A step's result with one observation of `view` (bearing `phi`, σ 0.02 rad), `estimated` or not.
COmniViewSLAM::TStepResult observing(size_t view, double phi, bool estimated = true)
{
    COmniViewSLAM::TStepResult r;
    COmniViewSLAM::TObservationRecord o;
    o.view = view;
    o.estimated = estimated;
    o.z.phi = phi;
    o.R = Eigen::Vector2d(4e-4, 1e-4).asDiagonal();
    r.observations.push_back(o);
    return r;
}

COmniViewSLAM::TStepResult starting(size_t view, COmniViewSLAM::TStepResult r = {})
{
    r.new_view = view;
    return r;
}

}  // namespace

// Per view, the last bearing estimated while the odometry path since the view's start is at most
// max_path (2 m), with the odometry from the view's step composed; bearings read farther on,
// those RANSAC did not estimate, and those of a camera the odometry did not move are left out.
TEST(ViewBearingPairing, KeepsEachViewsLastBearingWithinThePath)
{
    const mrpt::math::TPoint2D camera(0.1, -0.05);
    const TPose2D u(0.6, 0.02, 0.1), still(0, 0, 0);
    std::vector<Eigen::Matrix3d> Q;
    for (int s = 0; s < 7; s++)
        Q.push_back(Eigen::Vector3d(1e-4 * (s + 1), 2e-4, 1e-5).asDiagonal());
    const auto motion = [&](size_t s) {
        mrpt_vslam::core::TOdometryGaussian g;
        g.mean = u;
        g.cov = Q[s];
        return g;
    };
    std::vector<mrpt_vslam::core::TOdometryGaussian> motions;
    for (size_t s = 0; s < 7; s++) motions.push_back(motion(s));

    // the odometry path since view 0's start in the comments
    ViewBearingPairing pairing;
    pairing.add(u, Q[0], starting(0), camera);
    pairing.add(u, Q[1], observing(0, 3.0), camera);                // 0.6 m
    pairing.add(u, Q[2], starting(1, observing(0, 3.05)), camera);  // 1.2 m: view 0's last
    auto notEstimated = observing(1, 3.1);                          // view 1's
    notEstimated.observations.push_back(observing(0, 3.0, false).observations[0]);
    pairing.add(u, Q[3], notEstimated, camera);       // 1.8 m
    pairing.add(u, Q[4], observing(0, 2.9), camera);  // 2.4 m: beyond 2 m
    pairing.add(still, Q[5], starting(2), camera);
    pairing.add(still, Q[6], observing(2, 1.0), camera);  // no move

    const auto bearings = pairing.bearings();
    ASSERT_EQ(bearings.size(), 2u);
    const auto expect = [&](const mrpt_vslam::core::TEarlierPoseBearing& b, double phi, size_t from,
                            size_t to) {
        const auto [uc, Qc] = mrpt_vslam::core::composedOdometry(
            [&](size_t s) -> const mrpt_vslam::core::TOdometryGaussian& { return motions[s]; },
            from, to);
        EXPECT_DOUBLE_EQ(b.bearing, phi);
        EXPECT_DOUBLE_EQ(b.var, 4e-4);
        EXPECT_EQ(b.sensor, Eigen::Vector2d(0.1, -0.05));
        EXPECT_NEAR(b.u.x, uc.x, 1e-12);
        EXPECT_NEAR(b.u.y, uc.y, 1e-12);
        EXPECT_NEAR(b.u.phi, uc.phi, 1e-12);
        EXPECT_TRUE(b.Q.isApprox(Qc, 1e-12)) << b.Q << "\n" << Qc;
    };
    expect(bearings[0], 3.05, 0, 2);
    expect(bearings[1], 3.1, 2, 3);
}
