#include <gtest/gtest.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/viewmap/FeatureExistenceModel.h>

#include <cmath>
#include <stdexcept>
#include <vector>

using mrpt_vslam::viewmap::FeatureExistenceModel;

namespace {

/// n rays spread over azimuth (elevations 10°-60°); consistent where the azimuth is below
/// `consistent_sector` [rad].
struct TRing {
    Eigen::Matrix3Xd rays;
    std::vector<bool> consistent;
};

TRing ring(int n, double consistent_sector)
{
    TRing r;
    r.rays.resize(3, n);
    for (int k = 0; k < n; k++) {
        const double a = 2 * M_PI * (k + 0.5) / n;
        const double e = (10 + 50.0 * ((k * 7) % 11) / 10.0) * M_PI / 180;
        r.rays.col(k) << std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e);
        r.consistent.push_back(a < consistent_sector);
    }
    return r;
}

/// Existence p(d) = m + μ(d) of the fitted model in direction (azimuth, elevation).
double existenceAt(const FeatureExistenceModel& model, double prior, double a, double e)
{
    Eigen::MatrixXd x(1, 3);
    x << std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e);
    return prior + model.regression().predict(x).mean(0);
}

}  // namespace

TEST(FeatureExistenceModel, AllConsistentMeansFullExistence)
{
    mrpt::random::CRandomGenerator rng(1);
    FeatureExistenceModel model;
    const TRing r = ring(100, 10);
    const auto c = model.fit(r.rays, r.consistent, rng);
    EXPECT_EQ(c.points, 100u);
    EXPECT_DOUBLE_EQ(c.prior_mean, 1.0);
    EXPECT_DOUBLE_EQ(c.existence, 1.0);
    // The lower bound only drops by κσ where the model has no data (σ ≤ σ_f = 0.3).
    EXPECT_LE(c.lower_existence, 1.0);
    EXPECT_GE(c.lower_existence, 0.7 - 1e-9);
}

TEST(FeatureExistenceModel, LearnsWhereThePointsExist)
{
    mrpt::random::CRandomGenerator rng(2);
    FeatureExistenceModel model;
    const TRing r = ring(120, M_PI);  // consistent on the half with azimuth in [0, π)
    const auto c = model.fit(r.rays, r.consistent, rng);
    EXPECT_NEAR(c.prior_mean, 0.5, 1e-12);
    const double e = 35 * M_PI / 180;
    const double inside = existenceAt(model, c.prior_mean, M_PI / 2, e);
    const double outside = existenceAt(model, c.prior_mean, 3 * M_PI / 2, e);
    std::cout << "existence inside " << inside << ", outside " << outside << ", mean "
              << c.existence << ", lower " << c.lower_existence << "\n";
    EXPECT_GT(inside, 0.8);
    EXPECT_LT(outside, 0.2);
    EXPECT_NEAR(c.existence, 0.5, 0.1);
    EXPECT_LT(c.lower_existence, c.existence);
}

TEST(FeatureExistenceModel, ContentFallsAsTheConsistentSectorShrinks)
{
    double previous = 2;
    for (const double sector_deg : {360.0, 270.0, 180.0, 90.0, 0.0}) {
        mrpt::random::CRandomGenerator rng(3);
        FeatureExistenceModel model;
        const TRing r = ring(120, sector_deg * M_PI / 180 + 1e-9);
        const auto c = model.fit(r.rays, r.consistent, rng);
        EXPECT_LT(c.lower_existence, previous) << sector_deg;
        previous = c.lower_existence;
    }
    EXPECT_DOUBLE_EQ(previous, 0.0);
}

TEST(FeatureExistenceModel, SubsetIsSeededAndSizesAreChecked)
{
    FeatureExistenceModel::TOptions o;
    o.max_points = 40;
    const TRing r = ring(200, M_PI);
    mrpt::random::CRandomGenerator rng1(7), rng2(7), rng3(8);
    FeatureExistenceModel a(o), b(o), c(o);
    const auto ca = a.fit(r.rays, r.consistent, rng1);
    const auto cb = b.fit(r.rays, r.consistent, rng2);
    const auto cc = c.fit(r.rays, r.consistent, rng3);
    EXPECT_EQ(ca.points, 40u);
    EXPECT_EQ(ca.lower_existence, cb.lower_existence);
    EXPECT_NE(ca.prior_mean + ca.lower_existence, cc.prior_mean + cc.lower_existence);

    mrpt::random::CRandomGenerator rng(1);
    EXPECT_THROW(a.fit(r.rays, std::vector<bool>(3), rng), std::invalid_argument);
    const auto few = a.fit(r.rays.leftCols(2), {true, false}, rng);
    EXPECT_EQ(few.points, 0u);
    EXPECT_EQ(few.lower_existence, 0.0);
    o.max_points = 2;
    EXPECT_THROW(FeatureExistenceModel bad(o), std::invalid_argument);
}
