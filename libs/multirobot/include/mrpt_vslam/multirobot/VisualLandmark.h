#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace mrpt_vslam::multirobot {

/** One landmark of a particle's map (Gil et al. 2010, Eq. 3): the EKF of its 3D position in the
 *  map frame. Its descriptor d_j never changes after initialization, so it lives once in the
 *  LandmarkDescriptorPool shared by all particles, under the landmark's id. */
struct TVisualLandmark {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();  ///< μ [m]
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();   ///< Σ [m²]
    uint32_t times_seen = 0;  ///< measurements fused, the initializing one included
    uint32_t seen_by = 0;     ///< bit k set: robot k measured it (merged vs per-robot landmarks)
};

}  // namespace mrpt_vslam::multirobot
