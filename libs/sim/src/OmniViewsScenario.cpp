#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/ConfigReading.h>
#include <mrpt_vslam/sim/DatasetWriter.h>
#include <mrpt_vslam/sim/DeadReckoning.h>
#include <mrpt_vslam/sim/FrameObservations.h>
#include <mrpt_vslam/sim/OmniViewsScenario.h>
#include <mrpt_vslam/sim/RandomStreams.h>

#include <cstdio>

namespace mrpt_vslam::sim {

void OmniViewsScenario::loadConfig(const mrpt::config::CConfigFileBase& cfg)
{
    world.loadFromConfigFile(cfg, "World");
    textures.loadFromConfigFile(cfg, "Textures");
    renderer.loadFromConfigFile(cfg, "Camera");
    camera_on_robot = readPose3D(cfg, "CameraOnRobot", camera_on_robot);
    trajectory.loadFromConfigFile(cfg, "Trajectory");
    odometry.loadFromConfigFile(cfg, "Odometry");
    robot_radius = cfg.read_double("Robot", "radius", robot_radius);
    start_time = cfg.read_double("Dataset", "start_time", start_time);
    checkConfig(robot_radius > 0, "Robot", "radius", "> 0");
    checkConfig(start_time >= 0, "Dataset", "start_time", ">= 0");
    checkConfig(camera_on_robot.z() > 0 && camera_on_robot.z() < world.wall_height, "CameraOnRobot",
                "z", "in (0, [World] wall_height)");

    const std::vector<mrpt::math::TPose2D> path = trajectory.generate(trajectory.frames);
    for (size_t k = 0; k < path.size(); k++) {
        const double c = world.clearance(path[k].x, path[k].y);
        if (c >= robot_radius) continue;
        char where[96];
        std::snprintf(where, sizeof(where), " at (%.2f, %.2f) is %.2f m from walls or furniture",
                      path[k].x, path[k].y, c);
        throw core::UsageError("[Trajectory] waypoints: frame " + std::to_string(k) + where +
                               " (< [Robot] radius)");
    }
}

TSimulationSummary OmniViewsScenario::run(const TSimulationOptions& options)
{
    const std::vector<mrpt::math::TPose2D> poses = singleRobotPoses(name(), options, trajectory);
    const int n = static_cast<int>(poses.size());
    const TOfficeModel model = world.build(textures);

    odometry.reset(deriveStreamSeed(options.seed, RandomStream::Odometry));
    renderer.reset(deriveStreamSeed(options.seed, RandomStream::ImageNoise));

    DatasetWriter writer(options.out_prefix, options.write_images, {kImageLabel},
                         TPngCoding::HuffmanOnly);
    DeadReckoning track{mrpt::poses::CPose2D(poses.front())};
    TSimulationSummary summary;
    const int width = renderer.camera().width, height = renderer.camera().height;

    for (int k = 0; k < n; k++) {
        const double t = start_time + k * trajectory.frame_period;
        const mrpt::Clock::time_point stamp = mrpt::Clock::fromDouble(t);
        const mrpt::poses::CPose2D robot(poses[static_cast<size_t>(k)]);

        // Odometry: noisy increment from the previous frame (none before frame 0).
        const mrpt::poses::CPose2D increment = track.step(t, robot, odometry);
        mrpt::obs::CActionRobotMovement2D movement;
        movement.computeFromOdometry(increment, odometry.motionModel());
        movement.timestamp = stamp;
        mrpt::obs::CActionCollection actions;
        actions.insert(movement);

        const mrpt::poses::CPose3D robot_in_world(robot);
        mrpt::obs::CSensoryFrame sf;
        if (options.write_images) {
            const std::string file = DatasetWriter::imageFileName(kImageLabel, k);
            writer.writeImage(renderer.render(model.scene, robot_in_world + camera_on_robot), file);
            sf.insert(makeImageObservation(file, width, height, camera_on_robot, stamp));
        }
        sf.insert(makeGroundTruthObservation(robot_in_world, stamp));
        writer.writeFrame(actions, sf);

        summary.frames++;
        if (options.on_progress) options.on_progress(k + 1, n);
    }

    const core::LandmarkFile landmarks = model.cornerLandmarks();
    summary.path_length = track.path_length;
    writer.commit({{"groundtruth", track.ground_truth,
                    "ground truth: robot base pose in the world (timestamp x y z qx qy qz qw)"},
                   {"odometry", track.odometry,
                    "dead reckoning of the noisy odometry from the true initial pose"}},
                  landmarks,
                  "designed texture corners of the omni-views world (ground-truth landmarks) [m]");
    summary.details = std::to_string(model.corners.size()) + " ground-truth texture corners, " +
                      std::to_string(width) + "x" + std::to_string(height) + " OMNICAM images";
    return summary;
}

}  // namespace mrpt_vslam::sim
