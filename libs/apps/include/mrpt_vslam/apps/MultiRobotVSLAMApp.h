#pragma once

#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/TumTrajectory.h>

#include <memory>
#include <string>
#include <vector>

namespace mrpt_vslam::apps {

/** The `multirobot-vslam` driver: reads a rawlog with each robot's odometry and its
 *  range-bearing readings, pre-extracted landmarks or stereo images (turned into landmarks by one
 *  StereoFrontEnd per robot), found by class for one robot and by `<ROBOT>_...` label for a
 *  team (doc/multirobot.md, "Input"), runs
 *  CMultiRobotVisualSLAM through `CParticleFilter::executeOn()` and writes the run folder of
 *  doc/data-formats.md ("Run outputs") with one estimated path per robot.
 *
 *  Steps of run(): load the config, open the rawlog and the ground truth, then per team step:
 *  (stereo → landmarks) → filter step → progress; at the end paths, map, scene, run.json and
 *  metrics.json. Tests drive this class exactly as the binary does. */
class MultiRobotVSLAMApp {
  public:
    explicit MultiRobotVSLAMApp(core::AppArguments args);
    ~MultiRobotVSLAMApp();

    /// Loads the config and the inputs; throws core::UsageError for config problems and
    /// std::runtime_error for data problems, naming the file.
    void initialize();
    /// Processes the whole rawlog and writes the outputs.
    void run();
    /** Every configuration key the app reads, with the kind of value it takes (after
     *  initialize(), also when that failed): the options of the app. */
    std::vector<core::TReadKey> configKeys() const;

    /// @name Results (valid after run())
    /// @{
    std::vector<std::string> robots;
    std::vector<core::TumTrajectory> estimatedPaths;  ///< best particle's, one per robot
    std::vector<core::TumTrajectory> odometryPaths;   ///< dead reckoning from the same starts
    std::string outDir;
    /// @}

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace mrpt_vslam::apps
