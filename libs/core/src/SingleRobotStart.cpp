#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/system/filesystem.h>
#include <mrpt_vslam/core/EvalInputs.h>
#include <mrpt_vslam/core/SingleRobotStart.h>

#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::core {

void SingleRobotStart::loadFromConfig(const mrpt::config::CConfigFileBase& cfg,
                                      const std::string& section)
{
    m_section = section;
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
    m_file = groundTruthFileOf(groundTruthPrefix, robot, false);
    if (mrpt::system::fileExists(m_file))
        groundTruth = TumTrajectory::loadGroundTruth(m_file);
    else if (!args.groundTruth.empty())
        throw std::runtime_error("--ground-truth " + args.groundTruth +
                                 ": no such file: " + m_file);
}

const mrpt::math::TPose2D& SingleRobotStart::atFirstStep(double t, const mrpt::math::TPose2D& u)
{
    if (m_from_ground_truth && groundTruth)
        pose = groundTruthPoseAtStart(*groundTruth, t, u, m_file,
                                      "[" + m_section + "] initial_pose_from_ground_truth");
    return pose;
}

mrpt::math::TPose2D groundTruthPoseAtStart(const TumTrajectory& truth, double t,
                                           const mrpt::math::TPose2D& u, const std::string& file,
                                           const std::string& key, double tolerance)
{
    const int i = truth.nearestIndex(t, tolerance);
    if (i < 0)
        throw std::runtime_error(mrpt::format(
            "%s: no true pose within %g s of the rawlog's first step at %.6f s (the ground truth "
            "runs from %.6f to %.6f s), so the run cannot start from it: give the rawlog its own "
            "ground truth, or set %s = false",
            file.c_str(), tolerance, t, truth.timestamps.front(), truth.timestamps.back(),
            key.c_str()));
    // start ⊕ u = the true pose at the first step
    const mrpt::math::TPose3D& first = truth.poses[static_cast<size_t>(i)];
    return (mrpt::poses::CPose2D(first.x, first.y, first.yaw) + -mrpt::poses::CPose2D(u)).asTPose();
}

}  // namespace mrpt_vslam::core
