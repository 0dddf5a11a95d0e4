#include <mrpt_vslam/core/HungarianAssignment.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace mrpt_vslam::core {
namespace {

/** A cost ordered lexicographically: first the number of rows left out (only counted when leaving
 *  a row out is forbidden, i.e. `unassigned_row_cost` = +inf), then the sum of finite costs.
 *  Pairs with componentwise + and − form an ordered group, so the Hungarian method runs on them
 *  unchanged and the count part stays exact whatever the magnitude of the finite costs. */
struct TLexCost {
    int64_t dropped = 0;
    double cost = 0;

    TLexCost& operator+=(const TLexCost& o)
    {
        dropped += o.dropped;
        cost += o.cost;
        return *this;
    }
    TLexCost& operator-=(const TLexCost& o)
    {
        dropped -= o.dropped;
        cost -= o.cost;
        return *this;
    }
    friend TLexCost operator-(TLexCost x, const TLexCost& y) { return x -= y; }
    friend bool operator<(const TLexCost& x, const TLexCost& y)
    {
        return x.dropped != y.dropped ? x.dropped < y.dropped : x.cost < y.cost;
    }
};

// Larger than any reachable (dropped, cost): counts stay within ±4·(rows + 1).
constexpr TLexCost kUnreached{INT64_MAX / 4, 0.0};

void checkInputs(const Eigen::MatrixXd& cost, double unassigned_row_cost)
{
    if (std::isnan(unassigned_row_cost) || unassigned_row_cost == -HUGE_VAL) {
        throw std::invalid_argument(
            "solveHungarianAssignment: unassigned_row_cost must be finite or +inf, got " +
            std::to_string(unassigned_row_cost));
    }
    double max_abs = std::isfinite(unassigned_row_cost) ? std::abs(unassigned_row_cost) : 0.0;
    for (Eigen::Index i = 0; i < cost.rows(); i++) {
        for (Eigen::Index j = 0; j < cost.cols(); j++) {
            const double c = cost(i, j);
            if (std::isnan(c) || c == -HUGE_VAL) {
                throw std::invalid_argument("solveHungarianAssignment: cost(" + std::to_string(i) +
                                            ", " + std::to_string(j) + ") is " + std::to_string(c) +
                                            "; only finite values or +inf "
                                            "(forbidden pair) are allowed");
            }
            if (std::isfinite(c)) max_abs = std::max(max_abs, std::abs(c));
        }
    }
    // Potentials accumulate sums of up to ~2(n+m) costs; keep them away from overflow.
    const double terms = 4.0 * static_cast<double>(cost.rows() + cost.cols() + 1);
    if (!std::isfinite(max_abs * terms)) {
        throw std::invalid_argument(
            "solveHungarianAssignment: finite costs too large in magnitude (max |cost| = " +
            std::to_string(max_abs) + ") for overflow-free potentials");
    }
}

}  // namespace

TAssignment solveHungarianAssignment(const Eigen::MatrixXd& cost, double unassigned_row_cost)
{
    checkInputs(cost, unassigned_row_cost);
    const int n = static_cast<int>(cost.rows());
    const int m_real = static_cast<int>(cost.cols());

    // Pad with n "unassigned" columns, usable by any row, so every row can always be placed and
    // rows ≤ columns. Their cost is (0, unassigned_row_cost), or (1, 0) when dropping a row is
    // only a last resort (+inf).
    const bool may_drop = std::isfinite(unassigned_row_cost);
    const TLexCost drop_cost = may_drop ? TLexCost{0, unassigned_row_cost} : TLexCost{1, 0.0};
    const int m = m_real + n;
    // Row-major copy: the inner loop below scans one row.
    const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> cost_rows = cost;
    // Cost entry (i, j), 1-based; returns false for a forbidden pair.
    const auto entry = [&](int i, int j, TLexCost& out) {
        if (j > m_real) {
            out = drop_cost;
            return true;
        }
        const double c = cost_rows(i - 1, j - 1);
        if (c == HUGE_VAL) return false;
        out = TLexCost{0, c};
        return true;
    };

    // Shortest augmenting paths with row/column potentials (Jonker & Volgenant 1987; the
    // rectangular form with column 0 as the virtual source). Index 0 is the sentinel.
    std::vector<TLexCost> row_pot(n + 1), col_pot(m + 1), min_slack(m + 1);
    std::vector<int> col_row(m + 1, 0), way(m + 1, 0);
    std::vector<char> used(m + 1);
    for (int i = 1; i <= n; i++) {
        col_row[0] = i;
        int j0 = 0;
        std::fill(min_slack.begin(), min_slack.end(), kUnreached);
        std::fill(used.begin(), used.end(), 0);
        do {
            used[j0] = 1;
            const int i0 = col_row[j0];
            TLexCost delta = kUnreached;
            int j1 = 0;
            for (int j = 1; j <= m; j++) {
                if (used[j]) continue;
                TLexCost c;
                if (entry(i0, j, c)) {
                    TLexCost reduced = c - row_pot[i0];
                    reduced -= col_pot[j];
                    if (reduced < min_slack[j]) {
                        min_slack[j] = reduced;
                        way[j] = j0;
                    }
                }
                if (min_slack[j] < delta) {
                    delta = min_slack[j];
                    j1 = j;
                }
            }
            // Always reachable: the padding columns admit every row.
            for (int j = 0; j <= m; j++) {
                if (used[j]) {
                    row_pot[col_row[j]] += delta;
                    col_pot[j] -= delta;
                } else if (min_slack[j] < kUnreached) {
                    min_slack[j] -= delta;
                }
            }
            j0 = j1;
        } while (col_row[j0] != 0);
        // Flip the alternating path back to the source.
        do {
            const int j1 = way[j0];
            col_row[j0] = col_row[j1];
            j0 = j1;
        } while (j0 != 0);
    }

    TAssignment result;
    result.row_to_col.assign(n, -1);
    for (int j = 1; j <= m_real; j++) {
        if (col_row[j] != 0) result.row_to_col[col_row[j] - 1] = j - 1;
    }
    // Sum in row order from the input values (not the potentials) for a reproducible total.
    for (int i = 0; i < n; i++) {
        const int j = result.row_to_col[i];
        if (j >= 0) {
            result.total_cost += cost(i, j);
        } else {
            result.unassigned_rows++;
            if (may_drop) result.total_cost += unassigned_row_cost;
        }
    }
    return result;
}

}  // namespace mrpt_vslam::core
