#include <gtest/gtest.h>
#include <mrpt_vslam/core/HungarianAssignment.h>
#include <mrpt_vslam/core/LandmarkMetrics.h>

#include <cmath>
#include <limits>
#include <random>

using namespace mrpt_vslam::core;

namespace {

TLandmark lm(int id, double x, double y, double z = 0)
{
    TLandmark l;
    l.id = id;
    l.position = {x, y, z};
    return l;
}

}  // namespace

TEST(LandmarkMetrics, MatchesPermutedIdsByPosition)
{
    const std::vector<TLandmark> truth = {lm(0, 0, 0), lm(1, 5, 0), lm(2, 0, 5)};
    const std::vector<TLandmark> est = {lm(7, 0.1, 5), lm(8, 0, 0.2), lm(9, 5, 0, 0.3)};
    const auto m = evaluateLandmarks(est, truth, 1.5);
    EXPECT_EQ(m.num_matched, 3u);
    EXPECT_EQ(m.num_false, 0u);
    EXPECT_EQ(m.num_missed, 0u);
    EXPECT_EQ(m.num_duplicates, 0u);
    ASSERT_EQ(m.matches.size(), 3u);
    EXPECT_EQ(m.matches[0].est_id, 8);
    EXPECT_EQ(m.matches[1].est_id, 9);
    EXPECT_EQ(m.matches[2].est_id, 7);
    EXPECT_NEAR(m.matches[0].error.y, 0.2, 1e-12);
    EXPECT_NEAR(m.matches[1].error.z, 0.3, 1e-12);
    EXPECT_NEAR(m.matches[2].error_norm, 0.1, 1e-12);
    EXPECT_NEAR(m.error_mean, 0.2, 1e-12);
    EXPECT_NEAR(m.error_max, 0.3, 1e-12);
    EXPECT_NEAR(m.error_rmse, std::sqrt((0.01 + 0.04 + 0.09) / 3), 1e-12);
}

TEST(LandmarkMetrics, CountsFalseMissedAndDuplicates)
{
    const std::vector<TLandmark> truth = {lm(0, 0, 0), lm(1, 10, 0), lm(2, 20, 0)};
    const std::vector<TLandmark> est = {
        lm(0, 0.5, 0),   // matches true 0
        lm(1, -0.3, 0),  // closer to true 0 than est 0, so est 1 is the match
        lm(2, 10, 1),    // matches true 1
        lm(3, 50, 50),   // false: far from everything
    };                   // true 2 is missed
    const auto m = evaluateLandmarks(est, truth, 1.5);
    EXPECT_EQ(m.num_true, 3u);
    EXPECT_EQ(m.num_estimated, 4u);
    EXPECT_EQ(m.num_matched, 2u);
    EXPECT_EQ(m.num_missed, 1u);
    EXPECT_EQ(m.num_false, 2u);
    EXPECT_EQ(m.num_duplicates, 1u);
    EXPECT_EQ(m.duplicate_ids, std::vector<int>{0});
    EXPECT_EQ(m.false_ids, (std::vector<int>{0, 3}));
    EXPECT_EQ(m.matches[0].est_id, 1);
    EXPECT_EQ(m.matches[1].est_id, 2);
    EXPECT_FALSE(m.matches[2].matched());
    EXPECT_TRUE(std::isnan(m.matches[2].error_norm));
    EXPECT_NEAR(m.error_mean, (0.3 + 1.0) / 2, 1e-12);
    EXPECT_NEAR(m.error_max, 1.0, 1e-12);
}

TEST(LandmarkMetrics, PrefersMorePairsOverLowerCost)
{
    // Greedy nearest would pair est 0 with true 0 (0.1) and leave true 1 alone; the optimal
    // matching pairs both (est 0 → true 1 at 1.0, est 1 → true 0 at 1.0).
    const std::vector<TLandmark> truth = {lm(0, 0, 0), lm(1, 1.1, 0)};
    const std::vector<TLandmark> est = {lm(0, 0.1, 0), lm(1, -1, 0)};
    const auto m = evaluateLandmarks(est, truth, 1.05);
    EXPECT_EQ(m.num_matched, 2u);
    EXPECT_EQ(m.matches[0].est_id, 1);
    EXPECT_EQ(m.matches[1].est_id, 0);
    EXPECT_NEAR(m.error_max, 1.0, 1e-12);
}

TEST(LandmarkMetrics, CutoffForbidsFarPairs)
{
    const std::vector<TLandmark> truth = {lm(0, 0, 0)};
    const std::vector<TLandmark> est = {lm(5, 1.4, 0)};
    EXPECT_EQ(evaluateLandmarks(est, truth, 1.5).num_matched, 1u);
    const auto m = evaluateLandmarks(est, truth, 1.3);
    EXPECT_EQ(m.num_matched, 0u);
    EXPECT_EQ(m.num_missed, 1u);
    EXPECT_EQ(m.num_false, 1u);
    EXPECT_EQ(m.num_duplicates, 0u);
    EXPECT_TRUE(std::isnan(m.error_mean));
    EXPECT_THROW(evaluateLandmarks(est, truth, 0.0), std::invalid_argument);
}

TEST(LandmarkMetrics, EmptyListsAreHandled)
{
    const std::vector<TLandmark> truth = {lm(0, 0, 0), lm(1, 1, 1)};
    const auto noEst = evaluateLandmarks({}, truth, 1.0);
    EXPECT_EQ(noEst.num_missed, 2u);
    EXPECT_EQ(noEst.matches.size(), 2u);
    const auto noTruth = evaluateLandmarks(truth, {}, 1.0);
    EXPECT_EQ(noTruth.num_false, 2u);
    EXPECT_EQ(noTruth.num_duplicates, 0u);
}

// The assignment is solved per group of landmarks within the cut-off of each other: on a large
// random map it must pair exactly as many landmarks, at the same total distance, as one
// assignment over the whole matrix.
TEST(LandmarkMetrics, MatchesOneWholeAssignmentOnALargeMap)
{
    std::mt19937 gen(11);
    std::uniform_real_distribution<double> where(0, 30), noise(-0.6, 0.6);
    std::vector<TLandmark> truth, est;
    for (int i = 0; i < 400; i++) truth.push_back(lm(i, where(gen), where(gen), where(gen) / 10));
    for (int j = 0; j < 350; j++) {  // most near a true landmark, some near two, some false
        const auto& t = truth[static_cast<size_t>(j) % truth.size()].position;
        est.push_back(j % 7 == 0 ? lm(1000 + j, where(gen), where(gen))
                                 : lm(1000 + j, t.x + noise(gen), t.y + noise(gen), t.z));
    }
    const double cutoff = 0.8;
    const auto m = evaluateLandmarks(est, truth, cutoff);

    Eigen::MatrixXd cost(truth.size(), est.size());
    for (size_t i = 0; i < truth.size(); i++)
        for (size_t j = 0; j < est.size(); j++) {
            const double d = (est[j].position - truth[i].position).norm();
            cost(i, j) = d <= cutoff ? d : std::numeric_limits<double>::infinity();
        }
    const auto whole = solveHungarianAssignment(cost);
    EXPECT_EQ(m.num_matched, truth.size() - static_cast<size_t>(whole.unassigned_rows));
    EXPECT_NEAR(m.error_mean * static_cast<double>(m.num_matched), whole.total_cost, 1e-9);
    EXPECT_GT(m.num_matched, 250u);  // the instance is not trivial
    EXPECT_GT(m.num_false, 40u);
}
