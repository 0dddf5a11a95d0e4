#include <mrpt_vslam/core/HungarianAssignment.h>
#include <mrpt_vslam/core/LandmarkMetrics.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>

namespace mrpt_vslam::core {
namespace {
/** solveHungarianAssignment(cost) solved per connected component of the finite-cost pairs, each
 *  with its smaller side as rows: no pair links two components, so the optimum (most pairs, then
 *  least cost, the same seen from either side) is the union of the components' optima, and a map
 *  of a thousand landmarks no longer costs one solve cubic in the larger side. */
TAssignment assignByComponents(const Eigen::MatrixXd& cost)
{
    const auto rows = static_cast<size_t>(cost.rows()), cols = static_cast<size_t>(cost.cols());
    // union-find over the rows (0 .. rows-1) and the columns (rows .. rows+cols-1)
    std::vector<size_t> parent(rows + cols);
    std::iota(parent.begin(), parent.end(), size_t{0});
    const auto root = [&](size_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (size_t i = 0; i < rows; i++)
        for (size_t j = 0; j < cols; j++)
            if (std::isfinite(cost(i, j))) parent[root(i)] = root(rows + j);
    std::map<size_t, std::pair<std::vector<size_t>, std::vector<size_t>>> components;
    for (size_t i = 0; i < rows; i++) components[root(i)].first.push_back(i);
    for (size_t j = 0; j < cols; j++) components[root(rows + j)].second.push_back(j);

    TAssignment result{std::vector<int>(rows, -1), 0, 0};
    for (const auto& [r, component] : components) {
        const auto& [in_rows, in_cols] = component;
        if (in_cols.empty()) {
            result.unassigned_rows += static_cast<int>(in_rows.size());
            continue;
        }
        if (in_rows.empty()) continue;
        Eigen::MatrixXd sub(in_rows.size(), in_cols.size());
        for (size_t a = 0; a < in_rows.size(); a++)
            for (size_t b = 0; b < in_cols.size(); b++) sub(a, b) = cost(in_rows[a], in_cols[b]);
        // the solver's time grows with the square of the rows: the smaller side goes there
        const bool transposed = in_rows.size() > in_cols.size();
        const TAssignment part =
            solveHungarianAssignment(transposed ? Eigen::MatrixXd(sub.transpose()) : sub);
        size_t pairs = 0;
        for (size_t k = 0; k < part.row_to_col.size(); k++) {
            if (part.row_to_col[k] < 0) continue;
            const auto other = static_cast<size_t>(part.row_to_col[k]);
            const size_t a = transposed ? other : k, b = transposed ? k : other;
            result.row_to_col[in_rows[a]] = static_cast<int>(in_cols[b]);
            pairs++;
        }
        result.total_cost += part.total_cost;
        result.unassigned_rows += static_cast<int>(in_rows.size() - pairs);
    }
    return result;
}
}  // namespace

TLandmarkMetrics evaluateLandmarks(const std::vector<TLandmark>& estimated,
                                   const std::vector<TLandmark>& truth, double cutoff)
{
    if (!(cutoff > 0)) throw std::invalid_argument("evaluateLandmarks: cutoff must be > 0");
    constexpr double kInf = std::numeric_limits<double>::infinity();
    TLandmarkMetrics m;
    m.cutoff = cutoff;
    m.num_true = truth.size();
    m.num_estimated = estimated.size();

    // Rows: true landmarks, columns: estimates; pairs beyond the cut-off are forbidden.
    Eigen::MatrixXd dist(truth.size(), estimated.size());
    for (size_t i = 0; i < truth.size(); i++)
        for (size_t j = 0; j < estimated.size(); j++)
            dist(i, j) = (estimated[j].position - truth[i].position).norm();
    const Eigen::MatrixXd cost = (dist.array() <= cutoff).select(dist, kInf);
    const TAssignment assignment = assignByComponents(cost);

    std::vector<bool> estUsed(estimated.size(), false);
    double sum = 0, sumSq = 0;
    m.error_max = 0;
    for (size_t i = 0; i < truth.size(); i++) {
        TLandmarkMatch match;
        match.true_id = truth[i].id;
        match.true_position = truth[i].position;
        match.error_norm = std::numeric_limits<double>::quiet_NaN();
        const int j = assignment.row_to_col[i];
        if (j >= 0) {
            match.est_index = j;
            match.est_id = estimated[j].id;
            match.est_position = estimated[j].position;
            match.error = match.est_position - match.true_position;
            match.error_norm = dist(i, j);
            estUsed[j] = true;
            m.num_matched++;
            sum += match.error_norm;
            sumSq += match.error_norm * match.error_norm;
            m.error_max = std::max(m.error_max, match.error_norm);
        }
        m.matches.push_back(match);
    }
    m.num_missed = m.num_true - m.num_matched;
    if (m.num_matched > 0) {
        m.error_mean = sum / m.num_matched;
        m.error_rmse = std::sqrt(sumSq / m.num_matched);
    } else {
        m.error_mean = m.error_rmse = m.error_max = std::numeric_limits<double>::quiet_NaN();
    }

    for (size_t j = 0; j < estimated.size(); j++) {
        if (estUsed[j]) continue;
        m.false_ids.push_back(estimated[j].id);
        const bool nearMatched =
            std::any_of(m.matches.begin(), m.matches.end(), [&](const auto& mt) {
                return mt.matched() && dist(&mt - m.matches.data(), j) <= cutoff;
            });
        if (nearMatched) m.duplicate_ids.push_back(estimated[j].id);
    }
    m.num_false = m.false_ids.size();
    m.num_duplicates = m.duplicate_ids.size();
    return m;
}

}  // namespace mrpt_vslam::core
