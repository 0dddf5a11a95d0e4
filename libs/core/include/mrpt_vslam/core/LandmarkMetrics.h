#pragma once

#include <mrpt/math/TPoint3D.h>
#include <mrpt_vslam/core/LandmarkFile.h>

#include <vector>

namespace mrpt_vslam::core {

/** The estimated landmark matched to one true landmark. (The byte-packed TPoint3D members come
 *  first so their doubles stay 8-byte aligned.) */
struct TLandmarkMatch {
    mrpt::math::TPoint3D true_position;  ///< [m]
    mrpt::math::TPoint3D est_position;   ///< [m] valid when matched()
    mrpt::math::TPoint3D error;          ///< [m] est_position - true_position
    double error_norm = 0;               ///< [m] |error|, NaN when missed
    int true_id = -1;
    int est_index = -1;  ///< index into the estimated list, -1 when missed
    int est_id = -1;     ///< id of the matched estimate (when matched())

    bool matched() const { return est_index >= 0; }
};

/** Map accuracy after the optimal one-to-one matching of estimated to true landmarks. */
struct TLandmarkMetrics {
    double cutoff = 0;                    ///< [m] pairs farther apart were never matched
    std::vector<TLandmarkMatch> matches;  ///< one per true landmark, in ground-truth order
    size_t num_true = 0, num_estimated = 0;
    size_t num_matched = 0;
    size_t num_missed = 0;  ///< true landmarks with no estimate matched
    size_t num_false = 0;   ///< estimated landmarks matched to no true landmark
    /// Subset of the false ones lying within the cut-off of an already-matched true landmark.
    size_t num_duplicates = 0;
    std::vector<int> false_ids, duplicate_ids;  ///< ids of the estimated landmarks concerned
    /// @name Over matched landmarks [m] (NaN when none matched)
    /// @{
    double error_mean = 0, error_rmse = 0, error_max = 0;
    /// @}
};

/** Matches estimated to true landmarks one-to-one with solveHungarianAssignment(): cost =
 *  Euclidean distance (3D), pairs farther than `cutoff` [m] forbidden. The matching has the most
 *  pairs possible, and among those the least total distance. Throws std::invalid_argument when
 *  cutoff is not positive. */
TLandmarkMetrics evaluateLandmarks(const std::vector<TLandmark>& estimated,
                                   const std::vector<TLandmark>& truth, double cutoff);

}  // namespace mrpt_vslam::core
