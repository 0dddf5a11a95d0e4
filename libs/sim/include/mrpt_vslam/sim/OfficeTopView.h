#pragma once

#include <mrpt/img/CImage.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/sim/OfficeWorld.h>

#include <vector>

namespace mrpt_vslam::sim {

/** Colour top view of an office world, x to the right and y up, `pixels_per_metre`: floor
 *  white, walls black with doors as gaps in light brown, furniture in gray (partitions darker),
 *  ground-truth corners as small dots, and one path per robot (R1 red, R2 blue, R3 green, ...)
 *  with its start marked and labelled. */
mrpt::img::CImage drawOfficeTopView(const OfficeWorld& world, const TOfficeModel& model,
                                    const std::vector<std::vector<mrpt::math::TPose2D>>& paths,
                                    double pixels_per_metre = 40);

}  // namespace mrpt_vslam::sim
