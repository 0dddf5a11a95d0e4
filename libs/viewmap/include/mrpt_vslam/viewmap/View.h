#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/viewmap/ViewFeatures.h>

#include <Eigen/Core>
#include <cstdint>
#include <string>

namespace mrpt_vslam::viewmap {

/** One view of the map (doc/view-slam.md §1): the planar pose where an omnidirectional
 *  image was taken, the uncertainty of that pose and the image's feature points. */
struct TView {
    uint32_t id = 0;           ///< index of the view in its map (CViewMap::addView() sets it)
    mrpt::math::TPose2D pose;  ///< [m, m, rad] (x, y, yaw) in the map frame
    /// Covariance of (x, y, yaw) [m², m·rad, rad²], symmetric.
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    double timestamp = 0;  ///< [s] Unix time of the image
    /// The image's file as the rawlog refers to it (external storage name), empty if none.
    std::string image_file;
    TViewFeatures features;  ///< the image's feature points
};

}  // namespace mrpt_vslam::viewmap
