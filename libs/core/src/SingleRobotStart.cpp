#include <mrpt/core/bits_math.h>
#include <mrpt/system/filesystem.h>
#include <mrpt_vslam/core/EvalInputs.h>
#include <mrpt_vslam/core/SingleRobotStart.h>

#include <stdexcept>

namespace mrpt_vslam::core {

void SingleRobotStart::loadFromConfig(const mrpt::config::CConfigFileBase& cfg,
                                      const std::string& section)
{
    m_from_ground_truth =
        cfg.read_bool(section, "initial_pose_from_ground_truth", m_from_ground_truth);
    pose.x = cfg.read_double(section, "initial_x", 0);
    pose.y = cfg.read_double(section, "initial_y", 0);
    pose.phi = mrpt::DEG2RAD(cfg.read_double(section, "initial_yaw_deg", 0));
}

void SingleRobotStart::resolve(const AppArguments& args, const std::string& rawlog,
                               const std::string& robot)
{
    groundTruthPrefix = args.groundTruthPrefix(rawlog);
    const std::string tum = groundTruthFileOf(groundTruthPrefix, robot, false);
    if (mrpt::system::fileExists(tum))
        groundTruth = TumTrajectory::load(tum);
    else if (!args.groundTruth.empty())
        throw std::runtime_error("--ground-truth " + args.groundTruth + ": no such file: " + tum);
    if (m_from_ground_truth && groundTruth && !groundTruth->empty()) {
        const auto& p = groundTruth->poses.front();
        pose = {p.x, p.y, p.yaw};
    }
}

}  // namespace mrpt_vslam::core
