#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/ConfigReading.h>
#include <mrpt_vslam/sim/DatasetWriter.h>
#include <mrpt_vslam/sim/DeadReckoning.h>
#include <mrpt_vslam/sim/FrameObservations.h>
#include <mrpt_vslam/sim/PajdlaBaksteinInverse.h>
#include <mrpt_vslam/sim/RandomStreams.h>
#include <mrpt_vslam/sim/SportsHallScenario.h>

#include <cmath>

namespace mrpt_vslam::sim {

void SportsHallScenario::loadConfig(const mrpt::config::CConfigFileBase& cfg)
{
    camera.loadFromConfigFile(cfg, "Camera");
    camera_on_robot = readPose3D(cfg, "CameraOnRobot", camera_on_robot);
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
    const std::vector<mrpt::math::TPose2D> poses = singleRobotPoses(name(), options, trajectory);
    const int n = static_cast<int>(poses.size());

    odometry.reset(deriveStreamSeed(options.seed, RandomStream::Odometry));
    detections.reset(deriveStreamSeed(options.seed, RandomStream::Detections));
    renderer.reset(deriveStreamSeed(options.seed, RandomStream::ImageNoise));
    const PajdlaBaksteinInverse model(camera);
    const Eigen::Vector2d angular_std = detections.angularStd(camera, bearing_std_reference_theta);

    DatasetWriter writer(options.out_prefix, options.write_images, {kImageLabel});
    DeadReckoning track{mrpt::poses::CPose2D(poses.front())};
    TSimulationSummary summary;
    size_t light_bearings = 0, spurious_bearings = 0;

    for (int k = 0; k < n; k++) {
        const double t = k * trajectory.frame_period;
        const mrpt::Clock::time_point stamp = mrpt::Clock::fromDouble(start_time + t);
        const mrpt::poses::CPose2D robot(poses[k]);

        // Odometry: noisy increment from the previous frame (none before frame 0).
        const mrpt::poses::CPose2D increment = track.step(start_time + t, robot, odometry);
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
            const std::string file = DatasetWriter::imageFileName(kImageLabel, k);
            writer.writeImage(renderer.render(frame, lights.radius, model), file);
            sf.insert(
                makeImageObservation(file, camera.width, camera.height, camera_on_robot, stamp));
        }
        sf.insert(makeBearingObservation(
            frame, camera_on_robot,
            [&](double theta) { return detections.angularStd(camera, theta); }, angular_std,
            detections.max_light_theta, stamp));
        sf.insert(makeGroundTruthObservation(robot_in_world, stamp));
        writer.writeFrame(actions, sf);

        summary.frames++;
        light_bearings += frame.lights.size();
        spurious_bearings += frame.spurious.size();
        if (options.on_progress) options.on_progress(k + 1, n);
    }
    summary.path_length = track.path_length;
    writer.commit({{"groundtruth", track.ground_truth,
                    "ground truth: robot base pose in the world (timestamp x y z qx qy qz qw)"},
                   {"odometry", track.odometry,
                    "dead reckoning of the noisy odometry from the true initial pose"}},
                  lights.asLandmarkFile());
    summary.details = std::to_string(light_bearings) + " light and " +
                      std::to_string(spurious_bearings) + " spurious bearings";
    return summary;
}

}  // namespace mrpt_vslam::sim
