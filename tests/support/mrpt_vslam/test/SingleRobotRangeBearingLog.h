#pragma once

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/TumTrajectory.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace mrpt_vslam::test {

/** A single-robot range-bearing rawlog in MRPT's usual form, as a user's own data would be:
 *  one robot driving circles from the origin among landmarks, unlabelled `CObservationBearingRange`
 *  (landmarkID −1, `sensor_std_*` and the sensor's pose on the robot in the observation) and
 *  odometry as `CActionRobotMovement2D` (format #1) or `CObservationOdometry` (format #2);
 *  `NAME.groundtruth.tum` and `NAME.landmarks.txt` beside it. Deterministic for a seed. */
struct SingleRobotRangeBearingLog {
    /// Format #1 with an action before every frame (the first a zero increment), format #1 in
    /// simul-landmarks' order (the first frame with no action before it), or format #2.
    enum class Format { ActionsAndFrames, FrameFirst, ObservationsOnly };
    Format format = Format::ActionsAndFrames;
    size_t steps = 160;
    double std_range = 0.05;    ///< [m], true noise and sensor_std_range
    double std_bearing = 0.01;  ///< [rad], true noise and sensor_std_yaw
    /// [rad], true noise and sensor_std_pitch; > 0: the landmarks stand 0.6 m below, at and
    /// above the sensor's height in turn, and the readings carry their pitch (3D landmarks)
    double std_pitch = 0;
    double max_range = 4.5;                             ///< [m]
    double odometry_std_xy = 0.02;                      ///< [m] per step
    double odometry_std_phi = 0.01;                     ///< [rad] per step
    mrpt::poses::CPose3D sensor{0.2, 0, 0.3, 0, 0, 0};  ///< on the robot
    /// The sensor pose the observations state, where it is not the true one (a wrong
    /// calibration).
    std::optional<mrpt::poses::CPose3D> stated_sensor;
    /// A second sensor on the robot, at the first one's height: each frame then holds an
    /// observation of each, of the same landmarks where their fields of view overlap.
    std::optional<mrpt::poses::CPose3D> second_sensor;
    uint32_t seed = 1;

    /// The true landmarks, at the sensor's height (std_pitch = 0): a ring around the path, a
    /// few inside it.
    std::vector<mrpt::math::TPoint3D> landmarks() const
    {
        std::vector<mrpt::math::TPoint3D> pts;
        const auto z = [&] {
            return sensor.z() + (std_pitch > 0 ? 0.6 * (pts.size() % 3 - 1.0) : 0);
        };
        for (int i = 0; i < 16; i++) {
            const double a = 2 * M_PI * i / 16;
            pts.push_back({5.5 * std::cos(a), 3 + 5.5 * std::sin(a), z()});
        }
        for (const auto& [x, y] : {std::pair{1.0, 3.5}, {-1.5, 4.0}, {0.5, 1.5}})
            pts.push_back({x, y, z()});
        return pts;
    }

    /// Writes `prefix`.rawlog, `prefix`.groundtruth.tum, `prefix`.landmarks.txt.
    void write(const std::string& prefix) const
    {
        mrpt::random::CRandomGenerator rng(seed);
        const auto pts = landmarks();
        mrpt::io::CFileGZOutputStream file(prefix + ".rawlog");
        auto out = mrpt::serialization::archiveFrom(file);
        core::TumTrajectory truth;
        mrpt::poses::CPose2D pose(0, 0, 0), odometry = pose;  // the map frame's origin
        const double t0 = 1.0e9, dt = 0.5;
        for (size_t i = 0; i < steps; i++) {
            // 0.25 m per step on a circle of radius 3 m about (0, 3)
            const mrpt::poses::CPose2D delta =
                i == 0 ? mrpt::poses::CPose2D() : mrpt::poses::CPose2D(0.25, 0, 0.25 / 3);
            pose = pose + delta;
            const mrpt::poses::CPose2D noisy(
                delta.x() + rng.drawGaussian1D(0, i ? odometry_std_xy : 0),
                delta.y() + rng.drawGaussian1D(0, i ? odometry_std_xy : 0),
                delta.phi() + rng.drawGaussian1D(0, i ? odometry_std_phi : 0));
            odometry = odometry + noisy;
            const auto stamp = mrpt::Clock::fromDouble(t0 + dt * static_cast<double>(i));
            truth.push_back(mrpt::Clock::toDouble(stamp),
                            {pose.x(), pose.y(), 0, pose.phi(), 0, 0});

            const auto observe = [&](const mrpt::poses::CPose3D& on_robot) {
                auto obs = mrpt::obs::CObservationBearingRange::Create();
                obs->timestamp = stamp;
                obs->sensorLocationOnRobot = stated_sensor.value_or(on_robot);
                obs->minSensorDistance = 0;
                obs->maxSensorDistance = static_cast<float>(max_range);
                obs->sensor_std_range = static_cast<float>(std_range);
                obs->sensor_std_yaw = static_cast<float>(std_bearing);
                obs->sensor_std_pitch = static_cast<float>(std_pitch);
                const mrpt::poses::CPose3D sensorInMap = mrpt::poses::CPose3D(pose) + on_robot;
                for (const auto& p : pts) {
                    double r = 0, yaw = 0, pitch = 0;
                    sensorInMap.sphericalCoordinates(p, r, yaw, pitch);
                    if (r > max_range) continue;
                    mrpt::obs::CObservationBearingRange::TMeasurement m;
                    m.range = static_cast<float>(r + rng.drawGaussian1D(0, std_range));
                    m.yaw = static_cast<float>(yaw + rng.drawGaussian1D(0, std_bearing));
                    m.pitch = std_pitch > 0
                                  ? static_cast<float>(pitch + rng.drawGaussian1D(0, std_pitch))
                                  : 0;  // the landmarks are at the sensor's height
                    m.landmarkID = -1;
                    obs->sensedData.push_back(m);
                }
                return obs;
            };
            std::vector<mrpt::obs::CObservationBearingRange::Ptr> observations{observe(sensor)};
            if (second_sensor) observations.push_back(observe(*second_sensor));
            if (format != Format::ObservationsOnly) {
                if (format == Format::ActionsAndFrames || i > 0) {
                    mrpt::obs::CActionCollection acts;
                    mrpt::obs::CActionRobotMovement2D move;
                    move.timestamp = stamp;
                    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions model;
                    move.computeFromOdometry(noisy, model);
                    acts.insert(move);
                    out << acts;
                }
                mrpt::obs::CSensoryFrame sf;
                for (const auto& obs : observations) sf.insert(obs);
                out << sf;
            } else {
                mrpt::obs::CObservationOdometry odo;
                odo.timestamp = stamp;
                odo.odometry = odometry;
                out << odo;
                for (const auto& obs : observations) out << *obs;
            }
        }
        truth.save(prefix + ".groundtruth.tum", "true robot poses");
        core::LandmarkFile lms;
        int id = 0;
        for (const auto& p : pts) {
            core::TLandmark lm;
            lm.id = id++;
            lm.position = p;
            lms.landmarks.push_back(lm);
        }
        lms.save(prefix + ".landmarks.txt", "true landmarks");
    }
};

}  // namespace mrpt_vslam::test
