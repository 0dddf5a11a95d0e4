#include <gtest/gtest.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/HungarianAssignment.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

using mrpt_vslam::core::solveHungarianAssignment;
using mrpt_vslam::core::TAssignment;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Best (rows left out, cost) over all partial injective assignments, by enumeration. When
/// `unassigned_row_cost` is finite the count does not matter and is reported as 0.
struct TBrute {
    int dropped = 0;
    double cost = kInf;
};

void enumerate(const Eigen::MatrixXd& c, double drop_cost, int row, std::vector<char>& col_used,
               int dropped, double cost, TBrute& best)
{
    if (row == c.rows()) {
        const int key = std::isfinite(drop_cost) ? 0 : dropped;
        if (key < best.dropped || (key == best.dropped && cost < best.cost)) best = {key, cost};
        return;
    }
    enumerate(c, drop_cost, row + 1, col_used, dropped + 1,
              cost + (std::isfinite(drop_cost) ? drop_cost : 0.0), best);
    for (int j = 0; j < c.cols(); j++) {
        if (col_used[j] || c(row, j) == kInf) continue;
        col_used[j] = 1;
        enumerate(c, drop_cost, row + 1, col_used, dropped, cost + c(row, j), best);
        col_used[j] = 0;
    }
}

TBrute bruteForce(const Eigen::MatrixXd& c, double drop_cost)
{
    TBrute best{std::numeric_limits<int>::max(), kInf};
    std::vector<char> col_used(c.cols(), 0);
    enumerate(c, drop_cost, 0, col_used, 0, 0.0, best);
    return best;
}

/// Checks the assignment is a valid partial matching of allowed pairs and that its reported
/// totals match the matrix; returns the recomputed cost.
double checkValid(const Eigen::MatrixXd& c, double drop_cost, const TAssignment& a)
{
    EXPECT_EQ(a.row_to_col.size(), static_cast<size_t>(c.rows()));
    std::vector<int> col_count(c.cols(), 0);
    double cost = 0;
    int dropped = 0;
    for (int i = 0; i < c.rows(); i++) {
        const int j = a.row_to_col[i];
        if (j < 0) {
            EXPECT_EQ(j, -1);
            dropped++;
            if (std::isfinite(drop_cost)) cost += drop_cost;
            continue;
        }
        EXPECT_LT(j, c.cols());
        EXPECT_NE(c(i, j), kInf) << "forbidden pair (" << i << ", " << j << ") used";
        col_count[j]++;
        cost += c(i, j);
    }
    for (int n : col_count) EXPECT_LE(n, 1);
    EXPECT_EQ(a.unassigned_rows, dropped);
    EXPECT_DOUBLE_EQ(a.total_cost, cost);
    return cost;
}

}  // namespace

TEST(HungarianAssignment, MatchesBruteForceOnRandomSmallMatrices)
{
    mrpt::random::CRandomGenerator rng(1234);
    int cases = 0, cases_with_dropped = 0, cases_with_inf = 0;
    for (int rows = 0; rows <= 6; rows++) {
        for (int cols = 0; cols <= 6; cols++) {
            for (int rep = 0; rep < 200; rep++) {
                Eigen::MatrixXd c(rows, cols);
                const double p_forbidden = 0.15 * (rep % 5);  // 0 .. 0.6
                for (int i = 0; i < rows; i++) {
                    for (int j = 0; j < cols; j++) {
                        // Small integers (negative too) make many ties.
                        c(i, j) = rng.drawUniform(0.0, 1.0) < p_forbidden
                                      ? kInf
                                      : std::floor(rng.drawUniform(-3.0, 7.0));
                    }
                }
                const double drop_cost =
                    (rep % 2 == 0) ? kInf : std::floor(rng.drawUniform(-2.0, 8.0));
                const TBrute best = bruteForce(c, drop_cost);
                const TAssignment a = solveHungarianAssignment(c, drop_cost);
                const double cost = checkValid(c, drop_cost, a);
                ASSERT_EQ(cost, best.cost) << "rows=" << rows << " cols=" << cols << " rep=" << rep
                                           << " drop=" << drop_cost << "\n"
                                           << c;
                if (!std::isfinite(drop_cost)) {
                    ASSERT_EQ(a.unassigned_rows, best.dropped) << c;
                }
                // Same input → same output.
                EXPECT_EQ(solveHungarianAssignment(c, drop_cost).row_to_col, a.row_to_col);
                cases++;
                cases_with_dropped += a.unassigned_rows > 0;
                cases_with_inf += (c.array() == kInf).any();
            }
        }
    }
    EXPECT_EQ(cases, 7 * 7 * 200);
    // The random generator must exercise the interesting branches.
    EXPECT_GT(cases_with_dropped, 2500);
    EXPECT_GT(cases_with_inf, 4000);
}

TEST(HungarianAssignment, MatchesBruteForceOnRealValuedMatrices)
{
    mrpt::random::CRandomGenerator rng(99);
    for (int rep = 0; rep < 500; rep++) {
        const int rows = 1 + rep % 6, cols = 1 + (rep / 6) % 6;
        Eigen::MatrixXd c(rows, cols);
        for (int i = 0; i < rows; i++) {
            for (int j = 0; j < cols; j++) {
                c(i, j) = rng.drawUniform(0.0, 1.0) < 0.2 ? kInf : rng.drawGaussian1D(0.0, 100.0);
            }
        }
        const double drop_cost = (rep % 3 == 0) ? kInf : rng.drawUniform(-50.0, 150.0);
        const TBrute best = bruteForce(c, drop_cost);
        const TAssignment a = solveHungarianAssignment(c, drop_cost);
        ASSERT_NEAR(checkValid(c, drop_cost, a), best.cost, 1e-9 * (1 + std::abs(best.cost)));
        if (!std::isfinite(drop_cost)) {
            ASSERT_EQ(a.unassigned_rows, best.dropped);
        }
    }
}

TEST(HungarianAssignment, EmptyMatrices)
{
    const TAssignment none = solveHungarianAssignment(Eigen::MatrixXd(0, 4));
    EXPECT_TRUE(none.row_to_col.empty());
    EXPECT_EQ(none.total_cost, 0.0);
    EXPECT_EQ(none.unassigned_rows, 0);

    const TAssignment no_cols = solveHungarianAssignment(Eigen::MatrixXd(3, 0), 2.5);
    EXPECT_EQ(no_cols.row_to_col, std::vector<int>(3, -1));
    EXPECT_DOUBLE_EQ(no_cols.total_cost, 7.5);
    EXPECT_EQ(no_cols.unassigned_rows, 3);

    const TAssignment no_cols_inf = solveHungarianAssignment(Eigen::MatrixXd(2, 0));
    EXPECT_EQ(no_cols_inf.unassigned_rows, 2);
    EXPECT_EQ(no_cols_inf.total_cost, 0.0);
}

TEST(HungarianAssignment, MaximisesAssignedRowsBeforeCost)
{
    // Row 0 can take col 0 (cost 1) or col 1 (cost 1e12); row 1 only col 0.
    // Both rows assigned (cost 1e12 + 5) beats one row at cost 1 when leaving out is +inf.
    Eigen::MatrixXd c(2, 2);
    c << 1, 1e12, 5, kInf;
    const TAssignment a = solveHungarianAssignment(c);
    EXPECT_EQ(a.row_to_col, (std::vector<int>{1, 0}));
    EXPECT_EQ(a.unassigned_rows, 0);
    EXPECT_DOUBLE_EQ(a.total_cost, 1e12 + 5);

    // With a finite cost of leaving a row out, dropping row 1 becomes cheaper.
    const TAssignment b = solveHungarianAssignment(c, 100.0);
    EXPECT_EQ(b.row_to_col, (std::vector<int>{0, -1}));
    EXPECT_DOUBLE_EQ(b.total_cost, 101.0);
}

TEST(HungarianAssignment, HugeFiniteCostsAreNotConfusedWithForbidden)
{
    // A big-M approach with M = 1e15 would prefer dropping row 1 to paying 1e200.
    Eigen::MatrixXd c(2, 2);
    c << 0, kInf, kInf, 1e200;
    const TAssignment a = solveHungarianAssignment(c);
    EXPECT_EQ(a.row_to_col, (std::vector<int>{0, 1}));
    EXPECT_DOUBLE_EQ(a.total_cost, 1e200);
}

TEST(HungarianAssignment, AllForbiddenRowStaysUnassigned)
{
    Eigen::MatrixXd c(3, 2);
    c << 4, 2, kInf, kInf, 3, 7;
    const TAssignment a = solveHungarianAssignment(c);
    EXPECT_EQ(a.row_to_col, (std::vector<int>{1, -1, 0}));
    EXPECT_EQ(a.unassigned_rows, 1);
    EXPECT_DOUBLE_EQ(a.total_cost, 5.0);
}

TEST(HungarianAssignment, NewLandmarkColumnsAsInDataAssociation)
{
    // N_z = 2 measurements × (N = 2 landmarks + N_z "new landmark" columns), costs = −log-lik.
    // Measurement 0 fits landmark 1; measurement 1 fits nothing better than a new landmark.
    Eigen::MatrixXd c(2, 4);
    c << 9.0, 0.5, 4.0, kInf,  //
        8.0, 7.5, kInf, 4.0;
    const TAssignment a = solveHungarianAssignment(c);
    EXPECT_EQ(a.row_to_col, (std::vector<int>{1, 3}));
    EXPECT_DOUBLE_EQ(a.total_cost, 4.5);
}

TEST(HungarianAssignment, RejectsNanAndNegativeInfinity)
{
    Eigen::MatrixXd c = Eigen::MatrixXd::Ones(2, 3);
    EXPECT_NO_THROW(solveHungarianAssignment(c));
    c(1, 2) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(solveHungarianAssignment(c), std::invalid_argument);
    c(1, 2) = -kInf;
    EXPECT_THROW(solveHungarianAssignment(c), std::invalid_argument);
    c(1, 2) = 1.0;
    EXPECT_THROW(solveHungarianAssignment(c, std::numeric_limits<double>::quiet_NaN()),
                 std::invalid_argument);
    EXPECT_THROW(solveHungarianAssignment(c, -kInf), std::invalid_argument);
    c(0, 0) = 1e307;
    EXPECT_THROW(solveHungarianAssignment(c), std::invalid_argument);
}

TEST(HungarianAssignment, SquareIdentityLikeOptimum)
{
    // Closed form: cost(i, j) = (i − j)² has the identity as its unique zero-cost optimum.
    const int n = 40;
    Eigen::MatrixXd c(n, n);
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) c(i, j) = (i - j) * (i - j);
    }
    const TAssignment a = solveHungarianAssignment(c);
    for (int i = 0; i < n; i++) EXPECT_EQ(a.row_to_col[i], i);
    EXPECT_EQ(a.total_cost, 0.0);
}
