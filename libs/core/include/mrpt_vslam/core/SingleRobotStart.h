#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/TumTrajectory.h>

#include <optional>
#include <string>

namespace mrpt_vslam::core {

/** The start pose of a run from its ground truth `truth`: the pose before the first step (at
 *  time `t` [s], odometry increment `u`) from which `u` ends on the true pose nearest to `t`
 *  (within `tolerance`, the evaluation's pairing). That is the ground truth's first pose where
 *  it begins with the rawlog, a later one where the rawlog is cut from a longer one beside the
 *  longer one's ground truth; the nearest, not the first within `tolerance`: MRPT's
 *  simul-landmarks stamps its steps microseconds apart.
 *  \throw std::runtime_error naming `file`, its time span and `key` (the config key that takes
 *  the start pose from the ground truth) when no pose is that near. */
mrpt::math::TPose2D groundTruthPoseAtStart(const TumTrajectory& truth, double t,
                                           const mrpt::math::TPose2D& u, const std::string& file,
                                           const std::string& key, double tolerance = 0.05);

/** The ground truth and the start pose of a single-robot run (doc/data-formats.md): the ground
 *  truth `NAME.groundtruth.tum` beside the rawlog (or named by `--ground-truth`), and the start
 *  pose from the config keys of one section: `initial_pose_from_ground_truth` (default true: the
 *  true pose at the first step when there is ground truth), else `initial_x`, `initial_y` [m],
 *  `initial_yaw_deg`.
 *
 *  Usage: `start.loadFromConfig(cfg, "MyApp");` before `cfg.throwIfUnreadKeys()`, then
 *  `start.resolve(args, rawlog);` once the rawlog is known and `start.atFirstStep(t, u)` at the
 *  first step's time. */
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

    /** Sets pose from the ground truth, when it comes from there, for a first step at time
     *  `t` [s] with odometry increment `u` (groundTruthPoseAtStart()). \return pose */
    const mrpt::math::TPose2D& atFirstStep(double t, const mrpt::math::TPose2D& u);

    std::string groundTruthPrefix;             ///< `NAME` of the ground-truth files
    std::optional<TumTrajectory> groundTruth;  ///< when the ground-truth file exists
    mrpt::math::TPose2D pose;  ///< the start pose (from the config until atFirstStep())

  private:
    bool m_from_ground_truth = true;
    std::string m_section, m_file;  ///< for messages
};

}  // namespace mrpt_vslam::core
