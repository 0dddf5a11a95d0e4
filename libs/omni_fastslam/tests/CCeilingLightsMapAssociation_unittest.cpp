#include <gtest/gtest.h>
#include <mrpt/core/bits_math.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>

using mrpt::math::TPose2D;
using mrpt_vslam::omni_fastslam::BearingMeasurementModel;
using mrpt_vslam::omni_fastslam::CCeilingLightsMap;
using mrpt_vslam::omni_fastslam::TAssociationMethod;
using mrpt_vslam::omni_fastslam::TBearingMeasurement;

namespace {

const double kSigma = mrpt::DEG2RAD(1.0);

TBearingMeasurement measurement(double phi, double theta)
{
    TBearingMeasurement m;
    m.z = {phi, theta};
    m.Q = Eigen::Matrix2d::Identity() * kSigma * kSigma;
    return m;
}

/** Two landmarks whose predictions from `robot` differ by 3σ in φ, and measurements:
 *  z0 at 1.6σ from L0 (1.4σ from L1: slightly closer to L1), z1 at 0.2σ from L1,
 *  z2 a spurious detection far from both. */
struct TCrossedCase {
    CCeilingLightsMap map;
    TPose2D robot{0.4, -0.3, 0.2};
    std::vector<TBearingMeasurement> z;

    TCrossedCase()
    {
        const BearingMeasurementModel model = map.measurementModel();
        const Eigen::Vector3d camera = model.rayOriginInMap(robot);
        const Eigen::Matrix3d R = model.cameraInMap(robot).getRotationMatrix().asEigen();
        const double phi0 = 0.3, theta = 0.5;
        for (const double phi : {phi0, phi0 + 3 * kSigma})
            map.addLandmark(
                camera + 5.0 * R * BearingMeasurementModel::directionOfAngles({phi, theta}),
                Eigen::Matrix3d::Identity() * 1e-10);
        z = {measurement(phi0 + 1.6 * kSigma, theta), measurement(phi0 + 3.2 * kSigma, theta),
             measurement(-2.0, 1.2)};
    }
};

}  // namespace

TEST(CCeilingLightsMap, LandmarkLikelihoodsAreGaussianOfTheInnovation)
{
    TCrossedCase c;
    const Eigen::MatrixXd ll = c.map.landmarkLogLikelihoods(c.z, c.robot);
    ASSERT_EQ(ll.rows(), 3);
    ASSERT_EQ(ll.cols(), 2);
    const double log_norm = -std::log(2 * M_PI * kSigma * kSigma);
    EXPECT_NEAR(ll(0, 0), log_norm - 0.5 * 1.6 * 1.6, 1e-4);
    EXPECT_NEAR(ll(0, 1), log_norm - 0.5 * 1.4 * 1.4, 1e-4);
    EXPECT_NEAR(ll(1, 1), log_norm - 0.5 * 0.2 * 0.2, 1e-4);
    EXPECT_NEAR(ll(1, 0), log_norm - 0.5 * 3.2 * 3.2, 1e-4);
    EXPECT_NEAR(c.map.logPNew(c.z[0]), log_norm - 32, 1e-9);
}

TEST(CCeilingLightsMap, HungarianResolvesWhatGreedyMlGetsWrong)
{
    TCrossedCase c;
    c.map.insertionOptions.association_method = TAssociationMethod::ML;
    const auto ml = c.map.associate(c.z, c.robot);
    // Greedy: z0 grabs L1 (closest), z1 is left with L0 (3.2σ, still above P_new)
    EXPECT_EQ(ml.landmark_of_measurement, (std::vector<int>{1, 0, -1}));

    c.map.insertionOptions.association_method = TAssociationMethod::Hungarian;
    const auto hu = c.map.associate(c.z, c.robot);
    EXPECT_EQ(hu.landmark_of_measurement, (std::vector<int>{0, 1, -1}));
    // No candidates yet: the spurious measurement starts a new candidate
    EXPECT_EQ(hu.candidate_of_measurement, (std::vector<int>{-1, -1, -1}));
}

TEST(CCeilingLightsMap, SolveAssociationUsesNewLandmarkColumns)
{
    // 3 measurements, 2 landmarks; P_new = −5 for every measurement
    Eigen::MatrixXd ll(3, 2);
    ll << -1, -2,  //
        -1.5, -9,  //
        -20, -30;  // row 2 fits nothing better than P_new
    const Eigen::VectorXd p_new = Eigen::VectorXd::Constant(3, -5);
    // Hungarian: costs {1,2},{1.5,9},{20,30} + new = 5 → r0→L1 (2), r1→L0 (1.5), r2→new
    EXPECT_EQ(CCeilingLightsMap::solveAssociation(ll, p_new, TAssociationMethod::Hungarian),
              (std::vector<int>{1, 0, -1}));
    // ML: r0→L0 (−1), r1: L1 (−9) is worse than new (−5) → new
    EXPECT_EQ(CCeilingLightsMap::solveAssociation(ll, p_new, TAssociationMethod::ML),
              (std::vector<int>{0, -1, -1}));
    // −inf (undefined prediction) is never chosen
    ll(0, 1) = -std::numeric_limits<double>::infinity();
    EXPECT_EQ(CCeilingLightsMap::solveAssociation(ll, p_new, TAssociationMethod::Hungarian),
              (std::vector<int>{0, -1, -1}));
    EXPECT_TRUE(CCeilingLightsMap::solveAssociation(Eigen::MatrixXd(0, 2), Eigen::VectorXd(0),
                                                    TAssociationMethod::Hungarian)
                    .empty());
}

TEST(CCeilingLightsMap, SecondLevelAssociatesLeftoversToCandidates)
{
    TCrossedCase c;
    const std::vector<TBearingMeasurement> first{c.z[2]};
    c.map.insertMeasurements(first, c.robot);  // creates one candidate
    ASSERT_EQ(c.map.candidates().size(), 1u);
    // Same robot pose: the spurious direction again, plus a brand-new one far away
    const std::vector<TBearingMeasurement> second{c.z[0], c.z[1], measurement(-2.0, 1.2),
                                                  measurement(2.5, 0.9)};
    const auto a = c.map.associate(second, c.robot);
    EXPECT_EQ(a.landmark_of_measurement, (std::vector<int>{0, 1, -1, -1}));
    EXPECT_EQ(a.candidate_of_measurement, (std::vector<int>{-1, -1, 0, -1}));
    const Eigen::MatrixXd cl = c.map.candidateLogLikelihoods(second, c.robot);
    // identical ray from the same pose: innovation 0 with covariance Q + Q
    EXPECT_NEAR(cl(2, 0), -std::log(2 * M_PI * 2 * kSigma * kSigma), 1e-6);
    EXPECT_LT(cl(3, 0), c.map.logPNew(second[3]));
}
