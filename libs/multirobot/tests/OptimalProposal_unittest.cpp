// pfOptimalProposal of CMultiRobotVisualSLAM against brute force: for one measurement of one
// mapped landmark, and for one reading of another robot of the team, the particles' weight must
// be the evidence p(z | x_{t-1}, u, map) and their sampled poses the posterior
// p(x_t | x_{t-1}, u, z, map), both computed here by importance sampling from the motion prior
// with the exact (nonlinear) measurement model.
#include <gtest/gtest.h>
#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/maps/CLandmarksMap.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/multirobot/CMultiRobotVisualSLAM.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>

using namespace mrpt_vslam::multirobot;

namespace {
/// An odometry action without motion: its Gaussian is the noise floor alone.
mrpt::obs::CActionRobotMovement2D noiseOnly(double std_xy, double std_phi)
{
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions model;
    model.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
    model.gaussianModel.a1 = model.gaussianModel.a2 = 0;
    model.gaussianModel.a3 = model.gaussianModel.a4 = 0;
    model.gaussianModel.minStdXY = static_cast<float>(std_xy);
    model.gaussianModel.minStdPHI = static_cast<float>(std_phi);
    mrpt::obs::CActionRobotMovement2D act;
    act.computeFromOdometry(mrpt::poses::CPose2D(0, 0, 0), model);
    return act;
}

/// log N(v; 0, C) of v = R(θ) z + (x, y, 0) − target, C = target_cov + R(θ) Rz R(θ)ᵀ
double pointLogLikelihood(const Eigen::Vector3d& x, const Eigen::Vector3d& z,
                          const Eigen::Matrix3d& Rz, const Eigen::Vector3d& target,
                          const Eigen::Matrix3d& target_cov)
{
    Eigen::Matrix3d rot = Eigen::Matrix3d::Identity();
    rot.topLeftCorner<2, 2>() << std::cos(x[2]), -std::sin(x[2]), std::sin(x[2]), std::cos(x[2]);
    const Eigen::Vector3d v = rot * z + Eigen::Vector3d(x[0], x[1], 0) - target;
    const Eigen::Matrix3d C = target_cov + rot * Rz * rot.transpose();
    return -0.5 * (3 * std::log(2 * M_PI) + std::log(C.determinant()) + v.dot(C.llt().solve(v)));
}

struct TOneMeasurementCase {
    Eigen::Vector3d landmark{2.0, 0.6, 1.0};
    Eigen::Matrix3d landmark_cov = Eigen::Vector3d(0.02, 0.03, 0.02).cwiseAbs2().asDiagonal();
    Eigen::Vector3d z{2.05, 0.55, 1.0};  // robot frame: true pose ≈ (−0.03, 0.04, 1.5°)
    Eigen::Matrix3d R = Eigen::Vector3d(0.03, 0.02, 0.02).cwiseAbs2().asDiagonal();
    // no motion: the prior is the noise alone
    double std_xy = 0.06, std_phi = mrpt::DEG2RAD(3.0);

    mrpt_vslam::core::USurfDescriptor::TDescriptor descriptor() const
    {
        mrpt_vslam::core::USurfDescriptor::TDescriptor d{};
        d[0] = 1;
        return d;
    }

    mrpt::obs::CActionRobotMovement2D action() const { return noiseOnly(std_xy, std_phi); }

    mrpt::obs::CObservationVisualLandmarks::Ptr observation() const
    {
        auto obs = mrpt::obs::CObservationVisualLandmarks::Create();
        obs->sensorLabel = "R1_LANDMARKS";
        mrpt::maps::CLandmark lm;
        lm.pose_mean = mrpt::math::TPoint3D(z.x(), z.y(), z.z());
        lm.pose_cov_11 = static_cast<float>(R(0, 0));
        lm.pose_cov_22 = static_cast<float>(R(1, 1));
        lm.pose_cov_33 = static_cast<float>(R(2, 2));
        lm.pose_cov_12 = lm.pose_cov_13 = lm.pose_cov_23 = 0;
        mrpt::vision::CFeature f;
        f.x2[0] = f.x2[1] = f.y2[0] = f.y2[1] = 0;
        const auto d = descriptor();
        f.descriptors.SURF = std::vector<float>(d.begin(), d.end());
        lm.features.push_back(f);
        obs->landmarks.landmarks.push_back(lm);
        return obs;
    }

    /// the map-frame point seen from x (the exact model, no linearization)
    double logLikelihood(const Eigen::Vector3d& x) const
    {
        return pointLogLikelihood(x, z, R, landmark, landmark_cov);
    }
};

/// R1 reads R2, whose pose every particle knows exactly (it starts there, no spread).
struct TRobotReadingCase {
    mrpt::math::TPose2D seen{2.0, 0.6, 0.3};  // R2's start pose
    float range = 2.14f, bearing = 0.30f;     // true R1 pose ≈ (−0.05, 0.03, −1°)
    TRangeBearingNoise noise{0.04, mrpt::DEG2RAD(1.0), 0.01, {}, ""};
    double std_xy = 0.06, std_phi = mrpt::DEG2RAD(3.0);

    mrpt::obs::CObservationBearingRange::Ptr observation() const
    {
        auto obs = mrpt::obs::CObservationBearingRange::Create();
        obs->sensorLabel = "R1_ROBOTS";
        mrpt::obs::CObservationBearingRange::TMeasurement m;
        m.range = range;
        m.yaw = bearing;
        m.pitch = 0;
        m.landmarkID = 2;
        obs->sensedData.push_back(m);
        return obs;
    }

    double logLikelihood(const Eigen::Vector3d& x) const
    {
        const TLandmarkMeasurement m = measurementsFromBearingRange(*observation(), noise).at(0);
        return pointLogLikelihood(x, m.z, m.R, Eigen::Vector3d(seen.x, seen.y, 0),
                                  Eigen::Matrix3d::Zero());
    }
};

/** One step of `filter` (the framework's resampling not called); returns the first robot's
 *  prior covariance: its odometry's plus the filter's floor. */
Eigen::Matrix3d stepWithoutResampling(
    CMultiRobotVisualSLAM& filter, const mrpt::obs::CActionCollection& acts,
    const mrpt::obs::CSensoryFrame& sf,
    mrpt::bayes::CParticleFilter::TParticleFilterAlgorithm algorithm)
{
    mrpt::bayes::CParticleFilter::TParticleFilterOptions opts;
    opts.PF_algorithm = algorithm;
    filter.prediction_and_update(&acts, &sf, opts);

    mrpt::math::CMatrixDouble33 cov;
    mrpt::poses::CPose2D mean;
    acts.getActionByClass<mrpt::obs::CActionRobotMovement2D>()->poseChange->getCovarianceAndMean(
        cov, mean);
    Eigen::Matrix3d prior_cov = cov.asEigen();
    prior_cov.diagonal() += Eigen::Vector3d(filter.options.motion_noise_floor.std_xy,
                                            filter.options.motion_noise_floor.std_xy,
                                            filter.options.motion_noise_floor.std_phi)
                                .cwiseAbs2();
    return prior_cov;
}

/// Runs one step of the filter (M particles at the origin, all holding the landmark).
CMultiRobotVisualSLAM runOneStep(const TOneMeasurementCase& c,
                                 mrpt::bayes::CParticleFilter::TParticleFilterAlgorithm algorithm,
                                 size_t M, Eigen::Matrix3d& prior_cov)
{
    CMultiRobotVisualSLAM filter(CVisualLandmarksMap(), M, 17);
    filter.options.robots = {"R1"};
    filter.reset({mrpt::math::TPose2D(0, 0, 0)}, 0);
    CVisualLandmarksMap map(filter.m_particles[0].d->map.sharedDescriptorPool());
    map.insertionOptions = filter.m_particles[0].d->map.insertionOptions;
    map.insertionOptions.D0 = 1e9;  // the case is about the proposal, not the gate
    TVisualLandmark lm;
    lm.mean = c.landmark;
    lm.cov = c.landmark_cov;
    map.addLandmark(lm, c.descriptor());
    for (auto& p : filter.m_particles) p.d->map = map;

    mrpt::obs::CActionCollection acts;
    acts.insert(c.action());
    mrpt::obs::CSensoryFrame sf;
    sf.insert(c.observation());
    prior_cov = stepWithoutResampling(filter, acts, sf, algorithm);
    return filter;
}

/// One step of a two-robot filter in which R1 reads R2 (M particles, R1 at the origin).
CMultiRobotVisualSLAM runRobotReadingStep(
    const TRobotReadingCase& c, mrpt::bayes::CParticleFilter::TParticleFilterAlgorithm algorithm,
    size_t M, Eigen::Matrix3d& prior_cov)
{
    CMultiRobotVisualSLAM filter(CVisualLandmarksMap(), M, 17);
    filter.options.robots = {"R1", "R2"};
    filter.options.robot_reading_ids = {1, 2};
    filter.options.robot_reading_noise = c.noise;
    filter.options.initial_std_xy = filter.options.initial_std_phi = 0;
    filter.reset({mrpt::math::TPose2D(0, 0, 0), c.seen}, 0);

    mrpt::obs::CActionCollection acts;
    acts.insert(noiseOnly(c.std_xy, c.std_phi));
    acts.insert(noiseOnly(0.01, 0.01));  // R2 moves after R1's reading: no effect on it
    mrpt::obs::CSensoryFrame sf;
    sf.insert(c.observation());
    prior_cov = stepWithoutResampling(filter, acts, sf, algorithm);
    return filter;
}

struct TBruteForce {
    double log_evidence;
    Eigen::Vector3d mean;
    Eigen::Matrix3d cov;
};

template <class Case>
TBruteForce importanceSampling(const Case& c, const Eigen::Matrix3d& prior_cov)
{
    mrpt::random::CRandomGenerator rng(99);
    const Eigen::Matrix3d L = prior_cov.llt().matrixL();
    const int N = 400000;
    double sum_w = 0;
    Eigen::Vector3d sum_x = Eigen::Vector3d::Zero();
    Eigen::Matrix3d sum_xx = Eigen::Matrix3d::Zero();
    for (int i = 0; i < N; i++) {
        Eigen::Vector3d n;
        for (int k = 0; k < 3; k++) n[k] = rng.drawGaussian1D_normalized();
        const Eigen::Vector3d x = L * n;  // the prior's mean is the origin
        const double w = std::exp(c.logLikelihood(x));
        sum_w += w;
        sum_x += w * x;
        sum_xx += w * x * x.transpose();
    }
    TBruteForce b;
    b.log_evidence = std::log(sum_w / N);
    b.mean = sum_x / sum_w;
    b.cov = sum_xx / sum_w - b.mean * b.mean.transpose();
    return b;
}
/** Robot R1's particles (all with the same prior) against the brute force: each weight is the
 *  evidence, and their poses have the posterior's mean and covariance. */
void expectEvidenceAndPosterior(const CMultiRobotVisualSLAM& filter, const TBruteForce& exact,
                                const Eigen::Matrix3d& prior_cov)
{
    const auto M = static_cast<double>(filter.m_particles.size());
    for (const auto& p : filter.m_particles) EXPECT_NEAR(p.log_w, exact.log_evidence, 0.02);

    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : filter.m_particles)
        mean += Eigen::Vector3d(p.d->poses[0].x, p.d->poses[0].y, p.d->poses[0].phi);
    mean /= M;
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : filter.m_particles) {
        const Eigen::Vector3d d =
            Eigen::Vector3d(p.d->poses[0].x, p.d->poses[0].y, p.d->poses[0].phi) - mean;
        cov += d * d.transpose();
    }
    cov /= M - 1;
    // the measurement moves the pose by several prior σ in x, y, and shrinks the spread
    EXPECT_GT(std::abs(exact.mean.x()), 0.02);
    EXPECT_LT(exact.cov.trace(), 0.5 * prior_cov.trace());
    for (int i = 0; i < 3; i++) {
        EXPECT_NEAR(mean[i], exact.mean[i], 0.05 * std::sqrt(prior_cov(i, i))) << "component " << i;
        for (int j = 0; j < 3; j++)
            EXPECT_NEAR(cov(i, j), exact.cov(i, j),
                        0.06 * std::sqrt(exact.cov(i, i) * exact.cov(j, j)))
                << "covariance " << i << "," << j;
    }
}

/// Particles of the one-step tests: enough for the 0.02-0.06 tolerances against brute force.
constexpr size_t kParticles = 20000;

/// The mean of the standard proposal's weights (likelihoods at the sampled poses) is the evidence.
void expectMeanWeightIsTheEvidence(const CMultiRobotVisualSLAM& filter, const TBruteForce& exact)
{
    double sum = 0;
    for (const auto& p : filter.m_particles) sum += std::exp(p.log_w);
    EXPECT_NEAR(std::log(sum / static_cast<double>(filter.m_particles.size())), exact.log_evidence,
                0.05);
}
}  // namespace

TEST(OptimalProposal, WeightIsTheEvidenceAndSamplesFollowThePosterior)
{
    const TOneMeasurementCase c;
    const size_t M = kParticles;
    Eigen::Matrix3d prior_cov;
    const auto filter =
        runOneStep(c, mrpt::bayes::CParticleFilter::pfOptimalProposal, M, prior_cov);
    const auto exact = importanceSampling(c, prior_cov);
    ASSERT_EQ(filter.lastStepStats.associated, M);

    expectEvidenceAndPosterior(filter, exact, prior_cov);
}

// The standard proposal's weights are the likelihood at the sampled pose: their mean over the
// particles estimates the same evidence.
TEST(OptimalProposal, StandardProposalWeightsAverageToTheSameEvidence)
{
    const TOneMeasurementCase c;
    const size_t M = kParticles;
    Eigen::Matrix3d prior_cov;
    const auto filter =
        runOneStep(c, mrpt::bayes::CParticleFilter::pfStandardProposal, M, prior_cov);
    expectMeanWeightIsTheEvidence(filter, importanceSampling(c, prior_cov));
}

// A reading of another robot of the team is a measurement of an exactly known point: the same
// evidence and posterior, with both proposals.
TEST(OptimalProposal, ReadingOfAnotherRobotGivesTheEvidenceAndPosterior)
{
    const TRobotReadingCase c;
    const size_t M = kParticles;
    Eigen::Matrix3d prior_cov;
    const auto optimal =
        runRobotReadingStep(c, mrpt::bayes::CParticleFilter::pfOptimalProposal, M, prior_cov);
    const auto exact = importanceSampling(c, prior_cov);
    EXPECT_EQ(optimal.lastStepStats.robot_readings, 1u);
    expectEvidenceAndPosterior(optimal, exact, prior_cov);
    expectMeanWeightIsTheEvidence(
        runRobotReadingStep(c, mrpt::bayes::CParticleFilter::pfStandardProposal, M, prior_cov),
        exact);
}
