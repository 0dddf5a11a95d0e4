#pragma once

#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/TumTrajectory.h>

#include <memory>
#include <string>

namespace mrpt_vslam::apps {

/** The `view-slam` driver: reads a rawlog of odometry (actions or CObservationOdometry) with
 *  omnidirectional images (any label unless the config names one), runs COmniViewSLAM and
 *  writes the run folder (doc/data-formats.md, "Run outputs") plus the step and observation
 *  tables of doc/view-slam.md.
 *
 *  Steps of run(): load the config, open the rawlog and the ground truth, then per frame:
 *  filter step → tables → progress; at the end save paths, map, scene, run.json and
 *  metrics.json. Tests drive this class exactly as the binary does.
 */
class ViewSLAMApp {
  public:
    explicit ViewSLAMApp(core::AppArguments args);
    ~ViewSLAMApp();

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
    core::TumTrajectory estimatedPath;  ///< EKF robot estimate after each frame
    core::TumTrajectory odometryPath;   ///< dead reckoning from the same start
    std::string outDir;
    /// @}

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace mrpt_vslam::apps
