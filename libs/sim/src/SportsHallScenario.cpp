#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/ConfigReading.h>
#include <mrpt_vslam/sim/DatasetWriter.h>
#include <mrpt_vslam/sim/FrameObservations.h>
#include <mrpt_vslam/sim/PajdlaBaksteinInverse.h>
#include <mrpt_vslam/sim/RandomStreams.h>
#include <mrpt_vslam/sim/SportsHallScenario.h>

#include <cmath>

namespace mrpt_vslam::sim {

void SportsHallScenario::loadConfig(const mrpt::config::CConfigFileBase& cfg)
{
    camera.loadFromConfigFile(cfg, "Camera");
    const std::string s = "CameraOnRobot";
    camera_on_robot = mrpt::poses::CPose3D(
        cfg.read_double(s, "x", camera_on_robot.x()), cfg.read_double(s, "y", camera_on_robot.y()),
        cfg.read_double(s, "z", camera_on_robot.z()),
        readDegrees(cfg, s, "yaw_deg", camera_on_robot.yaw()),
        readDegrees(cfg, s, "pitch_deg", camera_on_robot.pitch()),
        readDegrees(cfg, s, "roll_deg", camera_on_robot.roll()));
    lights.loadFromConfigFile(cfg, "Lights");
    trajectory.loadFromConfigFile(cfg, "Trajectory");
    odometry.loadFromConfigFile(cfg, "Odometry");
    detections.loadFromConfigFile(cfg, "Detections");
    renderer.loadFromConfigFile(cfg, "Image");
    start_time = cfg.read_double("Dataset", "start_time", start_time);
    bearing_std_reference_theta =
        readDegrees(cfg, "Dataset", "bearing_std_reference_theta_deg", bearing_std_reference_theta);

    checkConfig(detections.max_light_theta <= camera.max_theta, "Detections", "max_light_theta_deg",
                "<= [Camera] max_theta_deg");
    checkConfig(start_time >= 0, "Dataset", "start_time", ">= 0");
    checkConfig(bearing_std_reference_theta > 0 && bearing_std_reference_theta <= camera.max_theta,
                "Dataset", "bearing_std_reference_theta_deg", "in (0, [Camera] max_theta_deg]");
}

TSimulationSummary SportsHallScenario::run(const TSimulationOptions& options)
{
    const int n = options.frames < 0 ? trajectory.frames : options.frames;
    if (n <= 0) throw core::UsageError("the number of frames must be > 0");
    const std::vector<mrpt::math::TPose2D> poses = trajectory.generate(n);

    odometry.reset(deriveStreamSeed(options.seed, RandomStream::Odometry));
    detections.reset(deriveStreamSeed(options.seed, RandomStream::Detections));
    renderer.reset(deriveStreamSeed(options.seed, RandomStream::ImageNoise));
    const PajdlaBaksteinInverse model(camera);
    const Eigen::Vector2d angular_std = detections.angularStd(camera, bearing_std_reference_theta);

    DatasetWriter writer(options.out_prefix, options.write_images);
    core::TumTrajectory ground_truth, odometry_path;
    mrpt::poses::CPose2D odometry_pose(poses.front());
    TSimulationSummary summary;

    for (int k = 0; k < n; k++) {
        const double t = k * trajectory.frame_period;
        const mrpt::Clock::time_point stamp = mrpt::Clock::fromDouble(start_time + t);
        const mrpt::poses::CPose2D robot(poses[k]);

        // Odometry: noisy increment from the previous frame (none before frame 0).
        mrpt::poses::CPose2D increment;
        if (k > 0) {
            const mrpt::poses::CPose2D true_increment = robot - mrpt::poses::CPose2D(poses[k - 1]);
            increment = odometry.simulateIncrement(true_increment);
            summary.path_length += true_increment.norm();
        }
        odometry_pose = odometry_pose + increment;
        ground_truth.push_back(start_time + t,
                               mrpt::math::TPose3D(robot.x(), robot.y(), 0, robot.phi(), 0, 0));
        odometry_path.push_back(start_time + t,
                                mrpt::math::TPose3D(odometry_pose.x(), odometry_pose.y(), 0,
                                                    odometry_pose.phi(), 0, 0));
        mrpt::obs::CActionRobotMovement2D movement;
        movement.computeFromOdometry(increment, odometry.motionModel());
        movement.timestamp = stamp;
        mrpt::obs::CActionCollection actions;
        actions.insert(movement);

        // Observations of the camera.
        const mrpt::poses::CPose3D robot_in_world(robot);
        const TFrameDetections frame =
            detections.simulate(robot_in_world + camera_on_robot, lights, t, model);
        mrpt::obs::CSensoryFrame sf;
        if (options.write_images) {
            writer.writeImage(renderer.render(frame, lights.radius, model), k);
            sf.insert(makeImageObservation(DatasetWriter::imageFileName(k), camera.width,
                                           camera.height, camera_on_robot, stamp));
        }
        sf.insert(makeBearingObservation(
            frame, camera_on_robot,
            [&](double theta) { return detections.angularStd(camera, theta); }, angular_std,
            detections.max_light_theta, stamp));
        sf.insert(makeGroundTruthObservation(robot_in_world, stamp));
        writer.writeFrame(actions, sf);

        summary.frames++;
        summary.light_bearings += frame.lights.size();
        summary.spurious_bearings += frame.spurious.size();
        if (options.on_progress) options.on_progress(k + 1, n);
    }
    writer.commit(ground_truth, odometry_path, lights.lights());
    return summary;
}

}  // namespace mrpt_vslam::sim
