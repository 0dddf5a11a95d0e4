#pragma once

#include <mrpt/math/TPose2D.h>

#include <optional>
#include <vector>

#include "MrclamDataset.h"

namespace mrpt_vslam::mrclam {

/** A robot's Vicon poses, interpolated in time: linear in x and y, along the shorter arc in
 *  heading. There is a pose at time t only where two Vicon samples bracket t no more than
 *  `max_gap` apart (or a sample falls exactly on t). */
class ViconTrack {
  public:
    static constexpr double kMaxGap = 0.5;  ///< [s] default longest gap to interpolate over

    explicit ViconTrack(const std::vector<TViconPose>& samples, double max_gap = kMaxGap)
        : m_samples(samples), m_max_gap(max_gap)
    {
    }

    /// The interpolated pose at time t [s], if the samples bracket it closely enough.
    std::optional<mrpt::math::TPose2D> poseAt(double t) const;

  private:
    const std::vector<TViconPose>& m_samples;
    double m_max_gap;
};

}  // namespace mrpt_vslam::mrclam
