#pragma once

#include <mrpt_vslam/sim/TexturedRectangle.h>

#include <vector>

namespace mrpt_vslam::sim {

/** A world made of textured rectangles (two-sided: a face hides what lies behind it from both
 *  sides), with the visibility query of the ground-truth statistics. */
class TexturedScene {
  public:
    std::vector<TexturedRectangle> rectangles;

    /** Whether `point` can be seen from `eye`: no rectangle crosses the segment between them
     *  closer than `tolerance` [m] to `point` (the face the point lies on does not hide it). */
    bool isVisibleFrom(const Eigen::Vector3d& point, const Eigen::Vector3d& eye,
                       double tolerance = 1e-3) const;
};

}  // namespace mrpt_vslam::sim
