#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/core/ObservationSelector.h>
#include <mrpt_vslam/core/RawlogEntrySource.h>

#include <deque>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** Filter steps (odometry action + sensory frame) from a rawlog in either format
 *  (doc/data-formats.md):
 *  - format #1: each `CActionCollection` with the `CSensoryFrame` that follows it; an action
 *    collection with no frame after it, or an empty one, is composed (mean and covariance, robot
 *    by robot) into the next step's, so that no odometry is lost (an empty frame is no step);
 *    a frame with no action before it (at the
 *    start of a rawlog, or right after another frame) was taken where the robot stood: its step
 *    stands still (see standsStill()), or moves by the odometry carried so far;
 *  - format #2 (observation-only): `CObservationOdometry` readings give the odometry, and every
 *    group of observations with the same timestamp that holds one matching `steps` becomes a
 *    frame, with a `CActionRobotMovement2D` built from the odometry increment since the previous
 *    frame and `motion_model` (a live source's time barrier closes the frame as a new
 *    timestamp does). The odometry of a frame is that of its time: a reading of the same time,
 *    else interpolated between the readings before and after it (the frame waits for the one
 *    after, up to kOdometryWait of the rawlog's time). The latest reading stands for it when
 *    none comes in that time, at the end of the data, when it is more than kOdometryWait older
 *    than the frame (a gap, or clocks that disagree), or for readings without a timestamp.
 *    Frames before every robot's first odometry reading are dropped
 *    (with standStillWithoutOdometry(): only those before any robot's).
 *
 *  Usage: `ActionFrameSource src(reader, {ObservationSelector::of<CObservationImage>("")},
 *  motion);` then `while (src.next(acts, sf)) ...`.
 */
class ActionFrameSource {
  public:
    /// How long a format-#2 frame waits for the odometry reading after its time [s].
    static constexpr double kOdometryWait = 1.0;

    /** How the format-#2 steps so far got each robot's odometry (a step of K robots counts K),
     *  and how many frames came before it. */
    struct TOdometryTiming {
        size_t at_step_time = 0;  ///< a reading of the step's own time
        size_t interpolated = 0;  ///< between the readings before and after it
        /// the latest reading: none came within kOdometryWait after, the data ended, it was
        /// older than that or later than the step, a reading had no timestamp, or (live) no
        /// waiting
        size_t latest_reading = 0;
        /// frames of the steps' observations passed over for coming before the first reading
        /// (of every robot; standStillWithoutOdometry(): of any robot)
        size_t frames_before_odometry = 0;
    };

    ActionFrameSource(RawlogEntrySource& reader, std::vector<ObservationSelector> steps,
                      const mrpt::obs::CActionRobotMovement2D::TMotionModelOptions& motion_model,
                      std::vector<std::string> odometry_labels = {});

    /** MRPT's Gaussian odometry model from an ini section: a1, a2, a3, a4, minStdXY [m],
     *  minStdPHI_deg (MRPT's defaults where absent). Throws UsageError naming the section and key
     *  unless a1-a4 are finite and >= 0 and the two minimum stds finite and > 0. */
    static mrpt::obs::CActionRobotMovement2D::TMotionModelOptions loadMotionModel(
        const mrpt::config::CConfigFileBase& cfg, const std::string& section);

    /** Format #2, a live team: a robot with no odometry reading since the last step (one that
     *  joins late, has gone silent, or whose readings are behind the others') stands exactly
     *  still in the step (see standsStill()) instead of holding every step back; its increment
     *  goes into its next step with a reading. No frame waits for a later reading: each takes
     *  the latest. */
    void standStillWithoutOdometry() { m_stand_still_without_odometry = true; }

    /** Whether `odometry` says the robot has not moved, with certainty (zero increment, zero
     *  covariance): a format-#1 frame with no action before it, or a robot with no odometry
     *  since the last step under standStillWithoutOdometry(). A filter leaves such a robot
     *  where it is, unless it has readings to fuse. */
    static bool standsStill(const mrpt::obs::CActionRobotMovement2D& odometry);

    /** The next step. \return false at the end of the rawlog. Throws std::runtime_error naming
     *  the rawlog and the entry for an action collection without usable planar odometry (see
     *  noOdometryError()), a CObservationOdometry of the robots whose pose is not finite, an
     *  observation of the steps whose sensor pose on the robot is not finite, and a second
     *  sensor where the run reads one: of the odometry of one robot (no odometry labels), or of
     *  a step selector with a `one_sensor_key`. */
    bool next(mrpt::obs::CActionCollection::Ptr& actions, mrpt::obs::CSensoryFrame::Ptr& frame);

    /// How the format-#2 steps handed out so far got their odometry (zero for format #1).
    const TOdometryTiming& odometryTiming() const { return m_odometry_timing; }

  private:
    /// "RAWLOG: entry N", for messages.
    std::string entryName(size_t entry) const;
    /** Why MRPT finds no planar odometry in the action collection of rawlog entry `entry`: none,
     *  one that is not finite, or one too uncertain; names the rawlog and the entry. */
    std::runtime_error noOdometryError(const mrpt::obs::CActionCollection& actions,
                                       size_t entry) const;
    /// Whether `obs` is of the observations that make a step (`steps` of the constructor).
    bool makesStep(const mrpt::obs::CObservation& obs) const;
    /** Throws std::runtime_error naming the rawlog and `entry` unless the sensor pose of `obs`,
     *  an observation of the steps, is finite, and unless it is of the sensor of the earlier ones
     *  where its selector reads one sensor (ObservationSelector::one_sensor_key). */
    void checkStepObservation(const mrpt::obs::CObservation& obs, size_t entry);
    /** "" if `obs` is of the first sensor met, `first` (which it sets on the first call); else
     *  the error naming the rawlog, `entry`, both labels and what the run `reads`. */
    std::string secondSensor(std::optional<std::string>& first, const mrpt::obs::CObservation& obs,
                             size_t entry, const std::string& reads) const;
    /// One robot's odometry reading (format #2).
    struct TOdometryReading {
        mrpt::poses::CPose2D pose;
        mrpt::Clock::time_point time;
        size_t entry = 0;  ///< of the rawlog
    };
    /// A closed format-#2 frame, waiting for the odometry at its time.
    struct TClosedFrame {
        mrpt::obs::CSensoryFrame::Ptr frame;
        mrpt::Clock::time_point time;
        /// Per robot: the reading before `time` while waiting for the one after; else the
        /// reading, or interpolation, that gives the odometry at `time` (none: stands still)
        std::vector<std::optional<TOdometryReading>> odometry;
        std::vector<bool> waiting;  ///< per robot
    };
    /// The pending frame, closed: its odometry resolved at once, or waiting (see TClosedFrame).
    void closePending();
    /// The pending frame, passed over: it makes no step, or comes before the odometry.
    void dropPending();
    /** A reading of robot `k` resolves the closed frames waiting for it at or before its time
     *  (interpolated), and is the latest before the others. */
    void resolveWaiting(size_t k, const TOdometryReading& reading);
    /** Frames that waited more than kOdometryWait before `now` (any time, at the end of the data)
     *  take the latest reading before their time. */
    void stopWaiting(std::optional<mrpt::Clock::time_point> now);
    /** A format-#2 odometry reading of rawlog entry `entry`: of a robot of the run, the latest
     *  (throws for a pose that is not finite); of a second sensor (no labels), the error thrown
     *  at the next step. */
    void readOdometry(const mrpt::obs::CObservationOdometry& odo, size_t entry);
    /** A format-#2 observation other than odometry, into the pending frame; throws for an
     *  observation of the steps whose sensor (label and class) the frame already holds. */
    void addToPending(const mrpt::obs::CObservation::Ptr& obs, size_t entry);
    /// Whether the oldest closed frame has its odometry.
    bool frontReady() const;
    /** The oldest closed frame as a step, built from the odometry since the last step.
     *  Throws noOdometryError() for an increment MRPT would pass over. */
    void emitFront(mrpt::obs::CActionCollection::Ptr& actions,
                   mrpt::obs::CSensoryFrame::Ptr& frame);
    /// Whether the pending format-#2 frame makes a step once closed.
    bool pendingIsStep() const;
    /// Whether every robot has had an odometry reading (standStillWithoutOdometry(): any robot).
    bool haveOdometry() const;
    /// A move of zero mean and zero covariance (standsStill()).
    static mrpt::obs::CActionRobotMovement2D standingMove();
    /// One standingMove() per robot.
    mrpt::obs::CActionCollection::Ptr standingStill() const;
    /** Format #1: the actions without a timestamp (a standing step's; some writers stamp none)
     *  take that of `frame`, the step's: of its first observation of the steps, else of its
     *  first. */
    void stampAtFrameTime(mrpt::obs::CActionCollection& actions,
                          const mrpt::obs::CSensoryFrame& frame) const;
    /// `later`'s odometry after m_carried's, robot by robot (CPosePDFGaussian composition).
    mrpt::obs::CActionCollection::Ptr afterCarried(const mrpt::obs::CActionCollection& later) const;

    RawlogEntrySource& m_reader;
    std::vector<ObservationSelector> m_steps;
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions m_motion_model;
    std::vector<std::string> m_odometry_labels;               ///< empty: one robot, any label
    std::vector<std::optional<TOdometryReading>> m_odometry;  ///< per robot: the latest reading
    /// Per robot: the odometry at the last step.
    std::vector<std::optional<mrpt::poses::CPose2D>> m_odometry_at_last_step;
    std::vector<bool> m_odometry_since_last_step;  ///< per robot
    /// Labels of the first sensor met: per selector of m_steps, and of the odometry (one robot).
    std::vector<std::optional<std::string>> m_step_sensors;
    std::optional<std::string> m_odometry_sensor;
    /// The error of a second odometry sensor, thrown at the next step (a rawlog with no step
    /// gets the error that says so)
    std::string m_second_odometry;
    mrpt::obs::CActionCollection::Ptr m_carried;  ///< format #1 odometry not yet in a step
    mrpt::obs::CSensoryFrame::Ptr m_pending;      ///< format #2 frame being assembled
    std::deque<TClosedFrame> m_closed;            ///< format #2 frames, oldest first
    mrpt::Clock::time_point m_pending_time;
    bool m_pending_is_step = false;
    bool m_stand_still_without_odometry = false;
    TOdometryTiming m_odometry_timing;
};

}  // namespace mrpt_vslam::core
