#include "MrclamImporter.h"

#include <mrpt/core/Clock.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt_vslam/sim/DatasetWriter.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "SpeedCommandOdometry.h"
#include "ViconTrack.h"

namespace mrpt_vslam::mrclam {
namespace {

std::string robotName(int number) { return "R" + std::to_string(number); }

mrpt::obs::CObservationOdometry odometryReading(int robot, mrpt::Clock::time_point stamp,
                                                const mrpt::math::TPose2D& pose,
                                                const TSpeedCommand& command)
{
    mrpt::obs::CObservationOdometry o;
    o.sensorLabel = robotName(robot) + "_ODOM";
    o.timestamp = stamp;
    o.odometry = mrpt::poses::CPose2D(pose);
    o.hasVelocities = true;
    o.velocityLocal = mrpt::math::TTwist2D(command.v, 0, command.w);
    return o;
}

/// The ground-truth TUM pose (z = 0) of a planar pose.
mrpt::math::TPose3D planar3D(const mrpt::math::TPose2D& p) { return {p.x, p.y, 0, p.phi, 0, 0}; }

/** Where the dead reckoning of a robot starts in the map frame: the Vicon pose at the window's
 *  start, else at the first step with Vicon, each with the odometry pose at that time. */
struct TDeadReckoningAnchor {
    mrpt::poses::CPose2D vicon, odometry;
};

TDeadReckoningAnchor anchorOf(const TMrclamRobot& robot, double start,
                              const std::vector<double>& step_times)
{
    const ViconTrack vicon(robot.ground_truth);
    SpeedCommandOdometry odometry(robot.commands);
    std::optional<mrpt::math::TPose2D> at = vicon.poseAt(start);
    double t = start;
    for (size_t k = 0; !at && k < step_times.size(); k++) {
        t = step_times[k];
        at = vicon.poseAt(t);
    }
    if (!at) return {mrpt::poses::CPose2D(), mrpt::poses::CPose2D(odometry.poseAt(start))};
    return {mrpt::poses::CPose2D(*at), mrpt::poses::CPose2D(odometry.poseAt(t))};
}

}  // namespace

double TRunningStats::std() const
{
    if (n == 0) return 0;
    const double m = mean();
    return std::sqrt(std::max(0.0, sum_sq / n - m * m));
}

mrpt::obs::CObservationBearingRange MrclamImporter::bearingRange(
    const std::string& label, mrpt::Clock::time_point stamp,
    const std::vector<TSubjectReading>& readings, bool keep_ids) const
{
    mrpt::obs::CObservationBearingRange obs;
    obs.sensorLabel = label;
    obs.timestamp = stamp;
    obs.minSensorDistance = 0;
    obs.maxSensorDistance = static_cast<float>(kMaxRange);
    obs.fieldOfView_yaw = static_cast<float>(mrpt::DEG2RAD(kFieldOfViewDeg));
    obs.sensorLocationOnRobot = mrpt::poses::CPose3D();
    obs.validCovariances = false;
    obs.sensor_std_range = static_cast<float>(m_options.std_range);
    obs.sensor_std_yaw = static_cast<float>(m_options.std_bearing);
    obs.sensor_std_pitch = 0;
    for (const TSubjectReading& r : readings) {
        mrpt::obs::CObservationBearingRange::TMeasurement m;
        m.range = static_cast<float>(r.range);
        m.yaw = static_cast<float>(r.bearing);
        m.pitch = 0;
        m.landmarkID = keep_ids ? r.subject : -1;
        m.covariance.setZero();
        obs.sensedData.push_back(m);
    }
    return obs;
}

void MrclamImporter::addResiduals(size_t k, const std::vector<TSubjectReading>& readings,
                                  const std::vector<ViconTrack>& vicon, TRunningStats& range,
                                  TRunningStats& bearing,
                                  std::map<int, TRunningStats>* by_range) const
{
    for (const TSubjectReading& r : readings) {
        const std::optional<mrpt::math::TPose2D> robot = vicon[k].poseAt(r.t);
        std::optional<mrpt::math::TPoint2D> seen;
        if (const auto landmark = m_dataset.landmarks.find(r.subject);
            landmark != m_dataset.landmarks.end())
            seen = landmark->second;
        for (size_t j = 0; j < m_dataset.robots.size(); j++)
            if (m_dataset.robots[j].number == r.subject)
                if (const auto pose = vicon[j].poseAt(r.t))
                    seen = mrpt::math::TPoint2D(pose->x, pose->y);
        if (!seen || !robot) continue;
        // predicted range and bearing of the subject from the robot's Vicon pose
        const double dx = seen->x - robot->x, dy = seen->y - robot->y;
        const double true_range = std::hypot(dx, dy);
        range.add(r.range - true_range);
        if (by_range) (*by_range)[static_cast<int>(true_range)].add(r.range - true_range);
        bearing.add(mrpt::math::wrapToPi(r.bearing - (std::atan2(dy, dx) - robot->phi)));
    }
}

MrclamImporter::TStepReadings MrclamImporter::selectReadings(TImportSummary& summary) const
{
    const double from = summary.dataset_start + m_options.start,
                 to = summary.dataset_start + m_options.end;
    TStepReadings steps;
    for (size_t k = 0; k < m_dataset.robots.size(); k++) {
        for (const TBarcodeReading& r : m_dataset.robots[k].readings) {
            if (r.t < from || r.t > to) {
                summary.outside_window++;
                continue;
            }
            const auto subject = m_dataset.subject_of_barcode.find(r.barcode);
            if (subject == m_dataset.subject_of_barcode.end()) {
                summary.dropped_unknown++;
                continue;
            }
            if (subject->second <= TMrclamDataset::kRobots &&
                (!m_options.keep_robot_measurements ||
                 std::none_of(
                     m_dataset.robots.begin(), m_dataset.robots.end(),
                     [&](const TMrclamRobot& robot) { return robot.number == subject->second; }))) {
                summary.dropped_robot++;
                continue;
            }
            steps[r.t][k].push_back({r.t, subject->second, r.range, r.bearing});
            summary.kept++;
        }
    }
    return steps;
}

TImportSummary MrclamImporter::run()
{
    TImportSummary summary;
    summary.dataset_start = m_dataset.firstTime();
    const TStepReadings steps = selectReadings(summary);
    if (steps.empty()) {
        std::ostringstream why;
        why << m_options.dataset_dir << ": no measurements of the chosen robots in the time window "
            << m_options.start << " to " << m_options.end << " s";
        throw std::runtime_error(why.str());
    }
    summary.steps = steps.size();
    summary.first_step = steps.begin()->first;
    summary.last_step = steps.rbegin()->first;
    std::vector<double> step_times;
    for (const auto& s : steps) step_times.push_back(s.first);

    const size_t n_robots = m_dataset.robots.size();
    std::vector<SpeedCommandOdometry> odometry;
    std::vector<ViconTrack> vicon;
    std::vector<TDeadReckoningAnchor> anchors;
    std::vector<sim::TTumFile> ground_truth(n_robots), dead_reckoning(n_robots);
    const double start = summary.dataset_start + m_options.start;
    for (const TMrclamRobot& r : m_dataset.robots) {
        odometry.emplace_back(r.commands);
        vicon.emplace_back(r.ground_truth);
        anchors.push_back(anchorOf(r, start, step_times));
        summary.robots[r.number] = {};
    }

    // The odometry pose of robot k at t, in non-decreasing t: the commands integrated, or with
    // --odometry-from-ground-truth the Vicon pose, else the last one carried on by the commands.
    std::vector<TDeadReckoningAnchor> last_vicon = anchors;
    const auto odometryPose = [&](size_t k, double t) {
        const mrpt::poses::CPose2D commands(odometry[k].poseAt(t));
        if (!m_options.odometry_from_ground_truth) return commands.asTPose();
        if (const auto truth = vicon[k].poseAt(t))
            last_vicon[k] = {mrpt::poses::CPose2D(*truth), commands};
        return (last_vicon[k].vicon + (commands - last_vicon[k].odometry)).asTPose();
    };
    if (m_options.odometry_from_ground_truth)  // the odometry frame is the map frame
        for (auto& a : anchors) a.odometry = a.vicon;

    sim::DatasetWriter writer(m_options.outPrefix(), false, {});
    for (size_t k = 0; k < n_robots; k++) {
        const TMrclamRobot& r = m_dataset.robots[k];
        writer.writeObservation(odometryReading(r.number, mrpt::Clock::fromDouble(start),
                                                odometryPose(k, start),
                                                odometry[k].commandAt(start)));
        const std::string name = robotName(r.number);
        ground_truth[k].name = "groundtruth_" + name;
        ground_truth[k].header_comment =
            "MRCLAM robot " + std::to_string(r.number) + ": Vicon pose interpolated at each step";
        dead_reckoning[k].name = "odometry_" + name;
        dead_reckoning[k].header_comment =
            "MRCLAM robot " + std::to_string(r.number) +
            (m_options.odometry_from_ground_truth
                 ? ": the odometry of the rawlog, Vicon poses (--odometry-from-ground-truth)"
                 : ": dead reckoning from the speed commands, starting at the Vicon pose");
    }

    for (const auto& [t, by_robot] : steps) {
        const mrpt::Clock::time_point stamp = mrpt::Clock::fromDouble(t);
        const double tum_time = mrpt::Clock::toDouble(stamp);  // the rawlog's time, exactly
        for (size_t k = 0; k < n_robots; k++) {
            const mrpt::math::TPose2D pose = odometryPose(k, t);
            writer.writeObservation(
                odometryReading(m_dataset.robots[k].number, stamp, pose, odometry[k].commandAt(t)));
            // dead reckoning in the map frame: G_a ⊕ (O_a⁻¹ ⊕ O(t))
            const mrpt::poses::CPose2D in_map =
                anchors[k].vicon + (mrpt::poses::CPose2D(pose) - anchors[k].odometry);
            dead_reckoning[k].poses.push_back(tum_time, planar3D(in_map.asTPose()));
        }
        for (const auto& [k, readings] : by_robot) {
            const int number = m_dataset.robots[k].number;
            std::vector<TSubjectReading> of_landmarks, of_robots;
            for (const TSubjectReading& r : readings)
                (r.subject <= TMrclamDataset::kRobots ? of_robots : of_landmarks).push_back(r);
            TRobotCounts& counts = summary.robots[number];
            if (!of_landmarks.empty()) {
                writer.writeObservation(bearingRange(robotName(number) + "_RB", stamp, of_landmarks,
                                                     m_options.keep_ids));
                addResiduals(k, of_landmarks, vicon, counts.range_residual, counts.bearing_residual,
                             &counts.range_residual_by_range);
                counts.measurements += of_landmarks.size();
                counts.observations++;
            }
            if (!of_robots.empty()) {  // robots know each other's barcodes: ids always kept
                writer.writeObservation(
                    bearingRange(robotName(number) + "_ROBOTS", stamp, of_robots, true));
                addResiduals(k, of_robots, vicon, counts.robot_range_residual,
                             counts.robot_bearing_residual);
                counts.robot_readings += of_robots.size();
            }
        }
        for (size_t k = 0; k < n_robots; k++) {
            const std::optional<mrpt::math::TPose2D> truth = vicon[k].poseAt(t);
            if (!truth) continue;
            const int number = m_dataset.robots[k].number;
            mrpt::obs::CObservationRobotPose obs;
            obs.sensorLabel = robotName(number) + "_GROUND_TRUTH";
            obs.timestamp = stamp;
            obs.pose.mean = mrpt::poses::CPose3D(mrpt::poses::CPose2D(*truth));
            obs.pose.cov.setZero();
            writer.writeObservation(obs);
            ground_truth[k].poses.push_back(tum_time, planar3D(*truth));
            summary.robots[number].ground_truth_poses++;
        }
    }

    core::LandmarkFile landmarks;
    for (const auto& [subject, xy] : m_dataset.landmarks) {
        core::TLandmark lm;
        lm.id = subject;
        lm.position = {xy.x, xy.y, 0};
        landmarks.landmarks.push_back(lm);
    }
    std::vector<sim::TTumFile> tum_files = ground_truth;
    tum_files.insert(tum_files.end(), dead_reckoning.begin(), dead_reckoning.end());
    writer.commit(tum_files, landmarks, "MRCLAM landmarks (Vicon): id = subject number, z = 0 [m]");
    return summary;
}

std::string TImportSummary::describe(const std::string& out_rawlog, double seconds) const
{
    std::string text = mrpt::format(
        "mrclam2rawlog: wrote %s: %zu steps from %.3f to %.3f (%.1f s to %.1f s after the "
        "dataset's first timestamp, %.1f s). Readings in the window: %zu kept, %zu of robots "
        "dropped, %zu of unknown barcodes dropped (%zu outside the window).",
        out_rawlog.c_str(), steps, first_step, last_step, first_step - dataset_start,
        last_step - dataset_start, last_step - first_step, kept, dropped_robot, dropped_unknown,
        outside_window);
    for (const auto& [number, c] : robots) {
        text += mrpt::format(
            " R%d: %zu landmark readings in %zu observations, %zu readings of robots, %zu "
            "ground-truth poses, residuals vs Vicon range %.3f +- %.3f m, bearing %.2f +- %.2f "
            "deg (%zu readings).",
            number, c.measurements, c.observations, c.robot_readings, c.ground_truth_poses,
            c.range_residual.mean(), c.range_residual.std(),
            mrpt::RAD2DEG(c.bearing_residual.mean()), mrpt::RAD2DEG(c.bearing_residual.std()),
            c.range_residual.n);
        if (c.range_residual_by_range.empty()) continue;
        std::string bins;
        for (const auto& [metres, s] : c.range_residual_by_range)
            bins += mrpt::format("%s%d-%d m %.3f +- %.3f (%zu)", bins.empty() ? "" : ", ", metres,
                                 metres + 1, s.mean(), s.std(), s.n);
        text += " Range residual by true range: " + bins + ".";
    }
    for (const auto& [number, c] : robots)
        if (c.robot_range_residual.n > 0)
            text += mrpt::format(
                " R%d reading robots: residuals vs Vicon range %.3f +- %.3f m, bearing %.2f +- "
                "%.2f deg (%zu readings).",
                number, c.robot_range_residual.mean(), c.robot_range_residual.std(),
                mrpt::RAD2DEG(c.robot_bearing_residual.mean()),
                mrpt::RAD2DEG(c.robot_bearing_residual.std()), c.robot_range_residual.n);
    return text + mrpt::format(" Import took %.2f s.\n", seconds);
}

}  // namespace mrpt_vslam::mrclam
