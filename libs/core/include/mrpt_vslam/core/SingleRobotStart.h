#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/TumTrajectory.h>

#include <optional>
#include <string>

namespace mrpt_vslam::core {

/** The ground truth and the start pose of a single-robot run (doc/data-formats.md): the ground
 *  truth `NAME.groundtruth.tum` beside the rawlog (or named by `--ground-truth`), and the start
 *  pose from the config keys of one section: `initial_pose_from_ground_truth` (default true: the
 *  first true pose when there is ground truth), else `initial_x`, `initial_y` [m],
 *  `initial_yaw_deg`.
 *
 *  Usage: `start.loadFromConfig(cfg, "MyApp");` before `cfg.throwIfUnreadKeys()`, then
 *  `start.resolve(args, rawlog);` once the rawlog is known. */
class SingleRobotStart {
  public:
    /// Reads the keys of `section`.
    void loadFromConfig(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
    /** Loads the ground truth of `rawlog` if there is one and sets pose: `NAME.groundtruth.tum`,
     *  or `NAME.groundtruth_<ROBOT>.tum` when `robot` is given (one robot of a multi-robot
     *  rawlog).
     *  \throw std::runtime_error naming the file when `--ground-truth` names a missing file. */
    void resolve(const AppArguments& args, const std::string& rawlog,
                 const std::string& robot = "");

    std::string groundTruthPrefix;             ///< `NAME` of the ground-truth files
    std::optional<TumTrajectory> groundTruth;  ///< when the ground-truth file exists
    mrpt::math::TPose2D pose;                  ///< the start pose

  private:
    bool m_from_ground_truth = true;
};

}  // namespace mrpt_vslam::core
