#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt_vslam/core/KLDSampling.h>

#include <cmath>
#include <set>

using mrpt::math::TPose2D;
using mrpt_vslam::core::kldResample;
using mrpt_vslam::core::kldSampleCount;

namespace {
mrpt_vslam::core::TKLDParams params(unsigned min_samples, unsigned max_samples)
{
    mrpt_vslam::core::TKLDParams p;
    p.KLD_binSize_XY = 0.1;
    p.KLD_binSize_PHI = 0.1;
    p.KLD_epsilon = 0.05;
    p.KLD_delta = 0.01;
    p.KLD_minSampleSize = min_samples;
    p.KLD_maxSampleSize = max_samples;
    return p;
}
}  // namespace

// Fox 2003, Eq. 12, evaluated by hand (z_0.99 = 2.3263).
TEST(KLDSampling, SampleCountIsFoxsBound)
{
    const auto p = params(1, 100000);
    EXPECT_EQ(kldSampleCount(2, p), 66u);
    EXPECT_EQ(kldSampleCount(10, p), 217u);
    auto q = p;
    q.KLD_epsilon = 0.02;
    EXPECT_EQ(kldSampleCount(100, q), 3367u);
    // the clamps
    EXPECT_EQ(kldSampleCount(0, params(10, 50)), 10u);
    EXPECT_EQ(kldSampleCount(1, params(10, 50)), 10u);
    EXPECT_EQ(kldSampleCount(10, params(10, 50)), 50u);
    q = params(10, 1000);
    q.KLD_minSamplesPerBin = 20;
    EXPECT_EQ(kldSampleCount(30, q), 600u);
}

// One bin: the minimum; the draws follow the weights.
TEST(KLDSampling, OneBinGivesTheMinimumDrawnByWeight)
{
    const auto p = params(20000, 100000);
    const std::vector<TPose2D> poses(2, TPose2D(1.02, -3.03, 0.51));
    mrpt::random::CRandomGenerator rng(1);
    const auto drawn = kldResample({std::log(0.25), std::log(0.75)}, poses, p, rng);
    ASSERT_EQ(drawn.size(), 20000u);
    double ones = 0;
    for (const size_t i : drawn) ones += i == 1;
    EXPECT_NEAR(ones / double(drawn.size()), 0.75, 0.01);
}

// Spread particles: the draws stop exactly where the bound of the bins drawn so far is met.
TEST(KLDSampling, StopsAtTheBoundOfTheOccupiedBins)
{
    const auto p = params(10, 100000);
    std::vector<TPose2D> poses;
    for (int i = 0; i < 400; i++)
        poses.emplace_back(0.1 * (i % 20) + 0.05, 0.1 * (i / 20) + 0.05, 0);
    const std::vector<double> log_w(poses.size(), -3.0);
    mrpt::random::CRandomGenerator rng(7);
    const auto drawn = kldResample(log_w, poses, p, rng);
    std::set<size_t> bins(drawn.begin(), drawn.end());  // one bin per particle here
    EXPECT_EQ(drawn.size(), kldSampleCount(bins.size(), p));
    EXPECT_GT(drawn.size(), 200u);
    // the same generator state gives the same draws
    mrpt::random::CRandomGenerator again(7);
    EXPECT_EQ(kldResample(log_w, poses, p, again), drawn);
    // the maximum
    mrpt::random::CRandomGenerator rng3(7);
    EXPECT_EQ(kldResample(log_w, poses, params(10, 50), rng3).size(), 50u);
}

TEST(KLDSampling, RefusesBadInput)
{
    mrpt::random::CRandomGenerator rng(1);
    EXPECT_THROW(kldResample({}, {}, params(1, 10), rng), std::invalid_argument);
    EXPECT_THROW(kldResample({0.0}, {TPose2D(), TPose2D()}, params(1, 10), rng),
                 std::invalid_argument);
    EXPECT_THROW(kldResample({0.0}, {TPose2D()}, params(20, 10), rng), std::invalid_argument);
    auto p = params(1, 10);
    p.KLD_binSize_XY = 0;
    EXPECT_THROW(kldResample({0.0}, {TPose2D()}, p, rng), std::invalid_argument);
}

// MRPT's [KLD_options] keys, KLD_binSize_PHI in degrees; what is saved loads back the same.
TEST(KLDSampling, ReadsAndWritesMrptsKeys)
{
    mrpt::config::CConfigFileMemory ini(
        "[KLD_options]\nKLD_binSize_XY = 0.3\nKLD_binSize_PHI = 4\nKLD_delta = 0.02\n"
        "KLD_epsilon = 0.1\nKLD_minSampleSize = 20\nKLD_maxSampleSize = 500\n"
        "KLD_minSamplesPerBin = 3\n");
    mrpt_vslam::core::TKLDParams p;
    p.loadFromConfigFile(ini, "KLD_options");
    EXPECT_DOUBLE_EQ(p.KLD_binSize_XY, 0.3);
    EXPECT_DOUBLE_EQ(p.KLD_binSize_PHI, 4 * M_PI / 180);
    EXPECT_DOUBLE_EQ(p.KLD_delta, 0.02);
    EXPECT_DOUBLE_EQ(p.KLD_epsilon, 0.1);
    EXPECT_EQ(p.KLD_minSampleSize, 20u);
    EXPECT_EQ(p.KLD_maxSampleSize, 500u);
    EXPECT_DOUBLE_EQ(p.KLD_minSamplesPerBin, 3);

    mrpt::config::CConfigFileMemory saved;
    p.saveToConfigFile(saved, "KLD_options");
    mrpt_vslam::core::TKLDParams q;
    q.loadFromConfigFile(saved, "KLD_options");
    EXPECT_NEAR(q.KLD_binSize_PHI, p.KLD_binSize_PHI, 1e-12);
    EXPECT_EQ(q.KLD_maxSampleSize, p.KLD_maxSampleSize);
    EXPECT_DOUBLE_EQ(q.KLD_minSamplesPerBin, p.KLD_minSamplesPerBin);
}
