#pragma once

#include <mrpt_vslam/core/USurfDescriptor.h>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mrpt_vslam::viewmap {

/** The feature points of one omnidirectional image (doc/view-slam.md §1): what a view
 *  stores and what the current image is matched with. Point k has its pixel, its SURF scale,
 *  the sign of its Laplacian, its unit ray in the robot frame (x forward, z up) and its U-SURF
 *  descriptor; all arrays have size() entries. */
struct TViewFeatures {
    Eigen::Matrix2Xf pixels{2, 0};        ///< [px] (column, row) per point
    std::vector<float> scales;            ///< [px] SURF scale s
    std::vector<int8_t> laplacian_signs;  ///< +1 / −1 (FastHessianDetector)
    Eigen::Matrix3Xd rays{3, 0};          ///< unit rays in the robot frame
    std::vector<core::USurfDescriptor::TDescriptor> descriptors;

    size_t size() const { return descriptors.size(); }
    bool empty() const { return descriptors.empty(); }
};

}  // namespace mrpt_vslam::viewmap
