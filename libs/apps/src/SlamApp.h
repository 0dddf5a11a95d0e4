#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt_vslam/apps/LiveView.h>
#include <mrpt_vslam/core/ActionFrameSource.h>
#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/ConfigChoice.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/ObservationSelector.h>
#include <mrpt_vslam/core/OutputDirectory.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/RunReport.h>
#include <mrpt_vslam/core/RunTimer.h>
#include <mrpt_vslam/core/SensorHeightOffset.h>
#include <mrpt_vslam/core/SensorPoseCorrection.h>
#include <mrpt_vslam/core/SensorTiltCorrection.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/core/UsageError.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mrpt_vslam::apps {

/// A sensor's pose on the robot as run.json gives it: "[x, y, z, yaw, pitch, roll]" (m, deg).
std::string poseJsonArray(const mrpt::poses::CPose3D& pose);
/// The same for a log line: "x X, y Y, z Z m, yaw A, pitch B, roll C deg".
std::string poseText(const mrpt::poses::CPose3D& pose);

/// One sensor's checks (doc/multirobot.md, "Checking the sensor poses"): its name, the
/// correction of its pose and, where it reads points in 3D, its tilt and its heights against
/// the other sensors' (by their names).
struct TSensorCheck {
    std::string sensor;
    core::TSensorPoseCorrection pose;
    std::optional<core::TSensorTiltCorrection> tilt;
    std::vector<std::pair<std::string, core::TSensorHeightOffset>> heights;
};

/** The sensor checks of a run: `app`'s line per sensor unless `quiet`, run.json
 *  `results.sensor_pose_check` and `timing.sensor_pose_check_s` (`seconds`), and a warning per
 *  sensor whose pose or readings look wrong. `read`: what the sensors read ("a landmark");
 *  `doc`: the page the warning points to. */
void reportSensorPoseChecks(const char* app, const char* read, const char* doc,
                            const std::vector<TSensorCheck>& checks, double seconds,
                            core::RunReport& report, bool quiet);

/// A SLAM app: its name (messages, progress line, run.json) and the ini section of its own keys.
struct TSlamAppId {
    const char* name;
    const char* section;
};
inline constexpr TSlamAppId kOmniFastSLAMId{"omni-fastslam", "OmniFastSLAM"};
inline constexpr TSlamAppId kMultiRobotVSLAMId{"multirobot-vslam", "MultiRobotVSLAM"};
inline constexpr TSlamAppId kViewSLAMId{"view-slam", "ViewSLAM"};

/** What the driver apps (omni-fastslam, multirobot-vslam, view-slam) do alike
 *  (doc/app-conventions.md); the app's own parts are the virtual functions below.
 *  - initialize(): the config (`--set`, `rawlog_file`, `random_seed`, the app's keys,
 *    `[MotionModel]`, then no unknown key), the rawlog's presence, the app's inputs, the `--gui`
 *    window;
 *  - run(): the run folder, the rawlog's filter steps (core::ActionFrameSource, both formats;
 *    or, with `--listen`, the readings streamed to the app, openInput())
 *    with the progress line, the step timer and the window redrawn after each step; then the
 *    app's results, `final.3Dscene`, `config.ini`, `run.json` and, with ground truth,
 *    `metrics.json`, then (without `--quiet`) where they are and the evaluation's figures;
 *    last, with `--gui` and without `--quiet`, the window until it is closed.
 *  The implementation of each app derives from it (through ParticleFilterApp for the particle
 *  filters). */
class SlamApp {
  public:
    virtual ~SlamApp();
    SlamApp(const SlamApp&) = delete;
    SlamApp& operator=(const SlamApp&) = delete;

    /// Loads the config and the inputs; throws core::UsageError for config problems and
    /// std::runtime_error for data problems, naming the file.
    void initialize();
    /// Processes the whole rawlog and writes the outputs.
    void run();
    /// Every configuration key the app reads (after initialize(), or after it failed).
    std::vector<core::TReadKey> configKeys() const { return cfg.readKeys(); }

  protected:
    /// \param name the app (messages, progress line, run.json); \param section its ini section
    SlamApp(core::AppArguments args, std::string name, std::string section);

    /// A config problem: "<config file>: <what>".
    core::UsageError usageError(const std::string& what) const;
    /// The ini section of the app's own keys.
    const std::string& ownSection() const { return m_section; }
    /// A key of the app's section as messages name it: "[SECTION] key".
    std::string ownKey(const std::string& key) const { return "[" + m_section + "] " + key; }
    /** A config problem from an option loader's exception, as one line: the value that did not
     *  fit its key (CheckedConfigFile::valueError()) if that was the cause, else its message. */
    core::UsageError configError(const std::exception& e) const;
    /** The value of `key` of the app's section, one of `choices` (name, value); absent, the
     *  first one. Any other name is a usage error that lists them (core::readChoice()). */
    template <class T>
    T readChoice(const std::string& key,
                 const std::vector<std::pair<std::string, T>>& choices) const
    {
        try {
            return core::readChoice(cfg, m_section, key, choices, choices.front().second);
        } catch (const std::invalid_argument& e) {
            throw usageError(e.what());
        }
    }

    /** For endSteps() when the rawlog gave no step: "<rawlog>: no frames with odometry and
     *  <inputs> (action / sensory-frame pairs, or CObservationOdometry readings); the rawlog has:
     *  <contents>". */
    std::runtime_error noFramesError(const std::string& inputs,
                                     const core::TRawlogSummary& contents) const;

    /** Runs `update`, one step of the filter, timed by `timer`; an exception becomes a
     *  std::runtime_error "<rawlog>: <where>: <message>". \return the step's duration [ms] */
    double timedStep(core::RunTimer& timer, const std::string& where,
                     const std::function<void()>& update) const;

    /** The time [s] of the current step, `stamp`: the time of what the step observes, else of
     *  its odometry, as the app takes it. The paths are stamped with it, so a step without one,
     *  or not after the step before it, is a std::runtime_error naming the rawlog and the step. */
    double stepTime(mrpt::Clock::time_point stamp);

    /// A path of (timestamp, pose) as a trajectory, one pose per timestamp: the last (a filter's
    /// path holds its start pose at the first step's time, then the first step's pose).
    static core::TumTrajectory asTrajectory(
        const std::vector<std::pair<double, mrpt::math::TPose2D>>& path);

    /// Where the entries come from: the rawlog (the default), or what the app listens to.
    virtual std::unique_ptr<core::RawlogEntrySource> openInput();

    /// @name Parts of the final scene
    /// @{
    /// A robot's odometry (red) and ground truth (black), labelled with `robot` if not empty.
    static void drawOdometryAndGroundTruth(mrpt::opengl::COpenGLScene& scene,
                                           const core::TumTrajectory& odometry,
                                           const std::optional<core::TumTrajectory>& groundTruth,
                                           const std::string& robot = "");
    /// The true landmarks `NAME.landmarks.txt` of the ground truth `NAME`, if the file exists
    /// (read once: initialize() reads them, to refuse a broken file before the run).
    const std::optional<core::LandmarkFile>& trueLandmarks(const std::string& groundTruthPrefix);
    /// Landmarks as black crosses.
    static void drawLandmarks(mrpt::opengl::COpenGLScene& scene, const core::LandmarkFile& file);
    /// @}

    const std::string name;  ///< the app
    core::AppArguments args;
    core::CheckedConfigFile cfg;
    std::string rawlog;
    uint32_t seed = 1;
    size_t steps = 0;  ///< filter steps done (frames of the rawlog)

  private:
    /// The app's keys, read after `rawlog_file` and `random_seed` of its section.
    virtual void loadConfig() = 0;
    /// With the config loaded and the rawlog present: ground truth, start poses, the filter.
    virtual void prepare() = 0;
    /// At the start of run(), once the run folder exists.
    virtual void startRun(const core::OutputDirectory& out);
    /// The observations that make a group of observations of an observation-only rawlog a step.
    virtual std::vector<core::ObservationSelector> stepObservations() const = 0;
    /// The labels of each robot's CObservationOdometry readings; empty: one robot, any label.
    virtual std::vector<std::string> odometryLabels() const;
    /// One step: the filter update (through timedStep()) and the app's bookkeeping.
    virtual void step(mrpt::obs::CActionCollection::Ptr actions, mrpt::obs::CSensoryFrame& frame,
                      core::RunTimer& timer) = 0;
    /// The estimate so far, in the `--gui` window.
    virtual void drawLive(mrpt::opengl::COpenGLScene& scene) const = 0;
    /** After the last step: throws a std::runtime_error when the rawlog (which holds
     *  `contents`) gave nothing to estimate from; the final estimates. */
    virtual void endSteps(const core::TRawlogSummary& contents) = 0;
    /// The estimates and the map in `out`, the final scene, the counts and results of run.json.
    virtual void writeResults(const core::OutputDirectory& out, mrpt::opengl::COpenGLScene& scene,
                              core::RunReport& report) = 0;
    /// `NAME` of the ground truth the run is evaluated against, if there is one.
    virtual std::optional<std::string> groundTruthName() const = 0;

    /// The results, `final.3Dscene`, `config.ini`, `run.json` and `metrics.json`; then, without
    /// `--quiet`, the folder and the evaluation's summary (core::printEvalSummary()) on stdout.
    void writeRunFolder(const core::OutputDirectory& out, const core::RunTimer& timer);
    /** What ran (inputs, effective config, seed, versions), its timing and, for an
     *  observation-only rawlog, how the steps got their odometry, in `report`: the part of
     *  run.json that a failed run writes too. */
    void describeRun(core::RunReport& report, const core::RunTimer& timer) const;

    const std::string m_section;
    /// Motion model of the actions built for observation-only rawlogs ([MotionModel]).
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions m_motionModel;
    /// How the steps so far got their odometry, for observation-only rawlogs (run.json counts).
    core::ActionFrameSource::TOdometryTiming m_odometryTiming;
    std::unique_ptr<LiveView> m_window;                      ///< --gui
    std::optional<mrpt::Clock::time_point> m_lastStepStamp;  ///< stepTime() of the step before
    /// trueLandmarks() read: the ground truth's `NAME` and its landmarks
    std::optional<std::pair<std::string, std::optional<core::LandmarkFile>>> m_trueLandmarks;
};

}  // namespace mrpt_vslam::apps
