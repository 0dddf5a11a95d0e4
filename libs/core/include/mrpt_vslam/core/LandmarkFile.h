#pragma once

#include <mrpt/math/TPoint3D.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** One map element read from a landmark or map file.
 *  (TPoint3D is byte-packed in MRPT; it comes first so its doubles stay 8-byte aligned.) */
struct TLandmark {
    mrpt::math::TPoint3D position;  ///< [m] landmark position; for views (x, y, 0)
    double yaw = 0;                 ///< [rad] view heading (view maps only)
    /// Covariance of (x, y, z) for landmarks or (x, y, yaw) for views [m², m·rad, rad²].
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    int id = -1;           ///< landmark id (the line order, from 0, when the file has none)
    bool has_cov = false;  ///< whether the file gave a covariance
};

/** Landmark files of ground truth and map files of runs (doc/data-formats.md):
 *  - ground truth `NAME.landmarks.txt`: `x y z` or `id x y z` per line;
 *  - run output `map.txt`: `id x y z cxx cxy cxz cyy cyz czz` (landmark maps), or
 *    `id x y yaw cxx cxy cxyaw cyy cyyaw cyawyaw` (view maps, recognised by a `#` header comment
 *    naming a `yaw` column).
 *  `#` starts a comment line. Every data line of a file has the same number of columns.
 */
class LandmarkFile {
  public:
    std::vector<TLandmark> landmarks;
    bool is_view_map = false;  ///< elements are views (x, y, yaw), not 3D points

    size_t size() const { return landmarks.size(); }
    bool empty() const { return landmarks.empty(); }

    /** Reads a file in any of the layouts above. Throws std::runtime_error "FILE:LINE: reason" on
     *  a missing file, a malformed line, a non-finite value, a column count other than 3, 4 or 10,
     *  a change of column count, a non-integer or repeated id, or a negative variance. */
    static LandmarkFile load(const std::string& file);
    /// load() of true landmarks, which must hold one: throws "FILE: no landmarks" otherwise.
    static LandmarkFile loadTrueLandmarks(const std::string& file);

    /** Writes atomically `id x y z` per line, or the 10-column layout when every element has a
     *  covariance, with a `#` header naming the columns. */
    void save(const std::string& file, const std::string& header_comment = {}) const;
};

}  // namespace mrpt_vslam::core
