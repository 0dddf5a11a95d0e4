#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

namespace mrpt_vslam::core {

/** Result of a rectangular linear assignment. */
struct TAssignment {
    /// For each row, the assigned column, or -1 when the row stays unassigned.
    std::vector<int> row_to_col;
    /// Sum of the costs of the assigned pairs plus `unassigned_row_cost` per unassigned row when
    /// that cost is finite. With `unassigned_row_cost` = +inf only the pairs are summed (rows left
    /// out are counted in `unassigned_rows`).
    double total_cost = 0;
    /// Number of rows left unassigned.
    int unassigned_rows = 0;
};

/** Minimum-cost rectangular linear assignment (Hungarian method, shortest augmenting paths à la
 *  Jonker-Volgenant), O(n²·(n + m)) time for n rows and m columns (O(N³) when n, m ≤ N);
 *  a random 300×300 matrix takes about 15 ms.
 *
 *  Each row is assigned to at most one column and each column to at most one row.
 *  - `cost(i, j) = +inf` forbids the pair (i, j).
 *  - A row may stay unassigned at cost `unassigned_row_cost`. With the default (+inf) the solver
 *    first maximises the number of assigned rows, then minimises the total cost of the pairs.
 *  - NaN or −inf costs, or a NaN / −inf `unassigned_row_cost`, throw std::invalid_argument, and
 *    so do finite costs so large (|c|·4(n+m+1) overflows) that the dual potentials could overflow.
 *  Rows are padded with n "unassigned" columns; the costs are compared as pairs (rows left out,
 *  sum of costs) so the count is exact and no big-M value competes with large finite costs.
 *  Ties are broken deterministically (same input → same output).
 */
TAssignment solveHungarianAssignment(
    const Eigen::MatrixXd& cost,
    double unassigned_row_cost = std::numeric_limits<double>::infinity());

}  // namespace mrpt_vslam::core
