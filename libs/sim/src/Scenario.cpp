#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/Scenario.h>
#include <mrpt_vslam/sim/WaypointTrajectory.h>

namespace mrpt_vslam::sim {

std::vector<mrpt::math::TPose2D> singleRobotPoses(const std::string& scenario,
                                                  const TSimulationOptions& options,
                                                  const WaypointTrajectory& trajectory)
{
    if (options.robots != -1 && options.robots != 1)
        throw core::UsageError(scenario + " has a single robot: --robots must be 1 or absent");
    const int n = options.frames < 0 ? trajectory.frames : options.frames;
    if (n <= 0) throw core::UsageError("the number of frames must be > 0");
    return trajectory.generate(n);
}

}  // namespace mrpt_vslam::sim
