#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/TumTrajectory.h>

#include <memory>
#include <string>
#include <vector>

namespace mrpt_vslam::apps {

/** The `omni-fastslam` driver: reads a rawlog of odometry with ceiling-light images or
 *  pre-extracted bearings (any label unless the config names one), runs COmniFastSLAM through
 *  `CParticleFilter::executeOn()` and writes the run folder (doc/data-formats.md,
 *  "Run outputs").
 *
 *  Steps of run(): load the config, open the rawlog and the ground truth, then per frame:
 *  (images → bearings) → filter step → progress; at the end save paths, map, scene, run.json
 *  and metrics.json. Tests drive this class exactly as the binary does.
 */
class OmniFastSLAMApp {
  public:
    explicit OmniFastSLAMApp(core::AppArguments args);
    ~OmniFastSLAMApp();

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
    core::TumTrajectory estimatedPath;  ///< best particle's path
    core::TumTrajectory odometryPath;   ///< dead reckoning from the same start
    std::string outDir;
    /// @}

  private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace mrpt_vslam::apps
