#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/math/TPose2D.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace mrpt_vslam::sim {

/** What one run of a scenario is asked to produce. */
struct TSimulationOptions {
    std::string out_prefix;    ///< DIR/NAME: files are NAME.rawlog, NAME_Images/, NAME.*.tum ...
    uint64_t seed = 1;         ///< master seed of every random stream
    int frames = -1;           ///< frames (steps) to simulate; −1 = the scenario's full run
    int robots = -1;           ///< robots of the team; −1 = the scenario's default
    bool write_images = true;  ///< false: no images (the other sensors only)
    /// Called after each frame with (frames done, frames total); may be empty.
    std::function<void(int, int)> on_progress;
};

/** What a run produced, for the closing line of vslam-sim and the tests. */
struct TSimulationSummary {
    int frames = 0;          ///< frames (steps) written; in a team every robot has one per step
    int robots = 1;          ///< robots simulated
    double path_length = 0;  ///< [m] ground-truth distance travelled, all robots together
    /// Scenario-specific counts in words, e.g. "2281 light and 109 spurious bearings".
    std::string details;
};

/** A simulated environment plus robot run that writes a dataset (layout: doc/data-formats.md).
 *
 *  1. Create it through createScenario(name).
 *  2. loadConfig() with the scenario's .ini (share/mrpt-vslam/config/vslam-sim/<name>.ini).
 *  3. run() writes the files; the same options and seed give byte-identical files. */
class Scenario {
  public:
    virtual ~Scenario() = default;
    /// Name used on the command line, e.g. "sports-hall".
    virtual std::string name() const = 0;
    /// Reads and validates every parameter; throws core::UsageError naming the bad key.
    virtual void loadConfig(const mrpt::config::CConfigFileBase& cfg) = 0;
    /// Simulates and writes the dataset; throws on any I/O error.
    virtual TSimulationSummary run(const TSimulationOptions& options) = 0;
};

class WaypointTrajectory;
/** The robot poses of a single-robot scenario's run: all frames of `trajectory`, or
 *  options.frames of them. \throw core::UsageError for --robots other than 1 or a frame count
 *  ≤ 0, naming `scenario` */
std::vector<mrpt::math::TPose2D> singleRobotPoses(const std::string& scenario,
                                                  const TSimulationOptions& options,
                                                  const WaypointTrajectory& trajectory);

}  // namespace mrpt_vslam::sim
