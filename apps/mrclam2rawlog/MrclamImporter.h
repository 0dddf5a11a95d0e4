#pragma once

#include <mrpt/core/Clock.h>
#include <mrpt/obs/CObservationBearingRange.h>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "MrclamCommandLine.h"
#include "MrclamDataset.h"

namespace mrpt_vslam::mrclam {

class ViconTrack;

/// Mean and standard deviation of a series, accumulated one value at a time.
struct TRunningStats {
    size_t n = 0;
    double sum = 0, sum_sq = 0;

    void add(double v)
    {
        n++;
        sum += v;
        sum_sq += v * v;
    }
    double mean() const { return n ? sum / n : 0; }
    /// Population standard deviation.
    double std() const;
};

/// What one robot contributed to the output.
struct TRobotCounts {
    size_t measurements = 0;        ///< landmark readings written (R<n>_RB)
    size_t observations = 0;        ///< R<n>_RB observations written (steps it observed in)
    size_t robot_readings = 0;      ///< readings of other robots written (R<n>_ROBOTS)
    size_t ground_truth_poses = 0;  ///< steps with an interpolated Vicon pose
    /** Reading minus the value predicted from the Vicon poses of the robot (interpolated at the
     *  reading's time) and of the landmark, over the landmark readings written: range [m] and
     *  bearing [rad] (wrapped to (−π, π]). */
    TRunningStats range_residual, bearing_residual;
    /// The landmark readings' range residual by true range, in 1 m bins (key: whole metres).
    std::map<int, TRunningStats> range_residual_by_range;
    /// The same over its readings of other robots (both robots' Vicon poses interpolated).
    TRunningStats robot_range_residual, robot_bearing_residual;
};

/// Counts of an import, for the summary and the tests.
struct TImportSummary {
    size_t steps = 0;            ///< distinct measurement timestamps
    size_t kept = 0;             ///< readings written
    size_t dropped_robot = 0;    ///< readings of robots' barcodes dropped (all, or of robots
                                 ///< not imported with keep_robot_measurements)
    size_t dropped_unknown = 0;  ///< readings of barcodes not in Barcodes.dat, dropped
    size_t outside_window = 0;   ///< readings before --start or after --end
    double first_step = 0, last_step = 0;  ///< [s] Unix time of the first and last step
    double dataset_start = 0;              ///< [s] first timestamp of the chosen robots' files
    std::map<int, TRobotCounts> robots;    ///< per robot number

    /** One paragraph for stdout: steps, time span, readings kept and dropped per reason, per
     *  robot counts and residuals vs Vicon, and the time taken. */
    std::string describe(const std::string& out_rawlog, double seconds) const;
};

/** Converts a loaded MRCLAM dataset into `OUT.rawlog` (observation-only, stock MRPT classes),
 *  `OUT.groundtruth_R<n>.tum`, `OUT.odometry_R<n>.tum` and `OUT.landmarks.txt`
 *  (doc/data-formats.md, "MRCLAM import").
 *
 *  1. Keeps the readings inside the time window whose barcode is a landmark (or one of the
 *     imported robots, with keep_robot_measurements); the distinct timestamps of those are the
 *     steps.
 *  2. Writes one R<n>_ODOM reading per robot at the window's start.
 *  3. At every step t: R<n>_ODOM for every robot (speed commands integrated up to t), R<n>_RB
 *     for every robot with landmark readings at t (landmarkID −1, or the subject with
 *     keep_ids), R<n>_ROBOTS for every robot with readings of other robots at t (landmarkID =
 *     the seen robot's number, always: each robot carries its own barcode), R<n>_GROUND_TRUTH
 *     for every robot with Vicon at t.
 *  4. Writes the TUM files and the landmarks, then renames the rawlog into place.
 *
 *  Throws std::runtime_error naming the dataset folder when the window has no readings, and
 *  naming the file on a failed write. */
class MrclamImporter {
  public:
    static constexpr double kMaxRange = 8.5;       ///< [m] dataset 7: longest reading 8.42 m
    static constexpr double kFieldOfViewDeg = 70;  ///< [deg] dataset 7: |bearing| ≤ 33.9°

    MrclamImporter(const TMrclamDataset& dataset, const TMrclamCommandLine& options)
        : m_dataset(dataset), m_options(options)
    {
    }

    TImportSummary run();

  private:
    /// A reading kept, with its barcode resolved to the subject.
    struct TSubjectReading {
        double t = 0;        ///< [s] Unix time
        int subject = 0;     ///< 1..5 robots, 6..20 landmarks
        double range = 0;    ///< [m]
        double bearing = 0;  ///< [rad]
    };
    /// Readings kept, by timestamp and then by robot index (into m_dataset.robots).
    using TStepReadings = std::map<double, std::map<size_t, std::vector<TSubjectReading>>>;
    TStepReadings selectReadings(TImportSummary& summary) const;
    /// The readings of one robot at one step, labelled `label`; landmarkID = the subject
    /// number if keep_ids, else −1.
    mrpt::obs::CObservationBearingRange bearingRange(const std::string& label,
                                                     mrpt::Clock::time_point stamp,
                                                     const std::vector<TSubjectReading>& readings,
                                                     bool keep_ids) const;
    /// Accumulates the residuals vs Vicon of robot k's readings (of landmarks or of robots);
    /// `vicon` holds the tracks of m_dataset.robots, in order; `by_range`, if given, gets the
    /// range residuals binned by true range.
    void addResiduals(size_t k, const std::vector<TSubjectReading>& readings,
                      const std::vector<ViconTrack>& vicon, TRunningStats& range,
                      TRunningStats& bearing,
                      std::map<int, TRunningStats>* by_range = nullptr) const;

    const TMrclamDataset& m_dataset;
    const TMrclamCommandLine& m_options;
};

}  // namespace mrpt_vslam::mrclam
