#include <mrpt_vslam/core/HungarianAssignment.h>
#include <mrpt_vslam/core/LandmarkMetrics.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mrpt_vslam::core {

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
    const auto assignment =
        truth.empty() || estimated.empty()
            ? TAssignment{std::vector<int>(truth.size(), -1), 0, static_cast<int>(truth.size())}
            : solveHungarianAssignment(cost);

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
