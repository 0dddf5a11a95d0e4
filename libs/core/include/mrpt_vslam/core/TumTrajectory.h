#pragma once

#include <mrpt/math/TPose3D.h>

#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** A timed trajectory in the TUM RGB-D text format, one pose per line:
 *  `timestamp x y z qx qy qz qw` (seconds, metres, unit quaternion). `#` lines are comments.
 *
 *  Timestamps are Unix seconds as double (`mrpt::Clock::toDouble()` of the rawlog's stamps).
 */
class TumTrajectory {
  public:
    std::vector<double> timestamps;          ///< [s], strictly increasing
    std::vector<mrpt::math::TPose3D> poses;  ///< pose of the robot in the map frame

    size_t size() const { return poses.size(); }
    bool empty() const { return poses.empty(); }
    void push_back(double t, const mrpt::math::TPose3D& pose);

    /** Reads a TUM file. Throws std::runtime_error "FILE:LINE: reason" on a missing file, a
     *  malformed line, a non-finite value, a non-unit quaternion or non-increasing timestamps. */
    static TumTrajectory load(const std::string& file);
    /// load() of a ground truth, which must hold a pose: throws "FILE: no poses" otherwise.
    static TumTrajectory loadGroundTruth(const std::string& file);

    /** Writes the file atomically (to FILE.tmp, then renamed), with an optional `#` header. */
    void save(const std::string& file, const std::string& header_comment = {}) const;

    /** Index of the pose whose timestamp is nearest to t, or -1 if none is within max_dt [s]. */
    int nearestIndex(double t, double max_dt) const;
};

}  // namespace mrpt_vslam::core
