#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/ConfigReading.h>
#include <mrpt_vslam/sim/DatasetWriter.h>
#include <mrpt_vslam/sim/DeadReckoning.h>
#include <mrpt_vslam/sim/FrameObservations.h>
#include <mrpt_vslam/sim/OfficeTeamScenario.h>
#include <mrpt_vslam/sim/OfficeTopView.h>
#include <mrpt_vslam/sim/RandomStreams.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace mrpt_vslam::sim {

namespace {

/// Corners closer than this to the image border [px] do not count as seen.
constexpr double kSeenMarginPx = 3;
/// Frames in a row a corner must be seen to count as tracked (Gil et al. 2010, Sec. 6: "Only the
/// observations found in 3 consecutive robot poses are integrated in the filter").
constexpr int kTrackedFrames = 3;

std::string trajectorySection(size_t index)
{
    return "Trajectory_" + OfficeTeamScenario::robotName(index);
}

std::string format(const char* fmt, double a, double b, double c)
{
    char text[128];
    std::snprintf(text, sizeof(text), fmt, a, b, c);
    return text;
}

}  // namespace

OfficeTeamScenario::OfficeTeamScenario()
    : camera_on_robot(0.1, 0.06, 0.5, mrpt::DEG2RAD(-90.0), 0, mrpt::DEG2RAD(-90.0))
{
}

std::string OfficeTeamScenario::robotName(size_t index) { return "R" + std::to_string(index + 1); }

std::string OfficeTeamScenario::label(size_t index, const std::string& sensor)
{
    return robotName(index) + "_" + sensor;
}

void OfficeTeamScenario::loadConfig(const mrpt::config::CConfigFileBase& cfg)
{
    world.loadFromConfigFile(cfg, "World");
    textures.loadFromConfigFile(cfg, "Textures");
    stereo.loadFromConfigFile(cfg, "StereoCamera");
    camera_on_robot = readPose3D(cfg, "CameraOnRobot", camera_on_robot);
    odometry.loadFromConfigFile(cfg, "Odometry");
    robot_radius = cfg.read_double("Robots", "radius", robot_radius);
    min_view_distance = cfg.read_double("Robots", "min_view_distance", min_view_distance);
    start_time = cfg.read_double("Dataset", "start_time", start_time);
    checkConfig(robot_radius > 0, "Robots", "radius", "> 0");
    checkConfig(min_view_distance >= 0, "Robots", "min_view_distance", ">= 0");
    checkConfig(start_time >= 0, "Dataset", "start_time", ">= 0");
    checkConfig(camera_on_robot.z() > 0 && camera_on_robot.z() < world.wall_height, "CameraOnRobot",
                "z", "in (0, [World] wall_height)");

    trajectories.clear();
    while (cfg.sectionExists(trajectorySection(trajectories.size()))) {
        const std::string s = trajectorySection(trajectories.size());
        WaypointTrajectory t;
        t.loadFromConfigFile(cfg, s);
        if (!trajectories.empty()) {
            checkConfig(t.frames == trajectories.front().frames, s, "frames",
                        "the same in every trajectory section");
            checkConfig(t.frame_period == trajectories.front().frame_period, s, "frame_period",
                        "the same in every trajectory section");
        }
        trajectories.push_back(t);
    }
    if (trajectories.size() < 2)
        throw core::UsageError(
            "[Trajectory_R1], [Trajectory_R2]: a team needs at least two "
            "trajectory sections");
    checkPaths();
}

std::vector<std::vector<mrpt::math::TPose2D>> OfficeTeamScenario::paths(int robots, int steps) const
{
    std::vector<std::vector<mrpt::math::TPose2D>> out;
    for (int r = 0; r < robots; r++)
        out.push_back(trajectories[static_cast<size_t>(r)].generate(steps));
    return out;
}

void OfficeTeamScenario::checkPaths() const
{
    // Heading of the optical axis on the robot, on the floor plane.
    const mrpt::math::CMatrixDouble33 R = camera_on_robot.getRotationMatrix();
    const double axis_yaw = std::atan2(R(1, 2), R(0, 2));
    for (size_t r = 0; r < trajectories.size(); r++) {
        const std::vector<mrpt::math::TPose2D> path =
            trajectories[r].generate(trajectories[r].frames);
        for (size_t k = 0; k < path.size(); k++) {
            const mrpt::math::TPose2D& p = path[k];
            const double c = world.clearance(p.x, p.y);
            if (c < robot_radius)
                throw core::UsageError(
                    "[" + trajectorySection(r) + "] waypoints: frame " + std::to_string(k) +
                    format(" at (%.2f, %.2f) is %.2f m from walls or furniture", p.x, p.y, c) +
                    " (< [Robots] radius)");
            const mrpt::poses::CPose3D cam =
                mrpt::poses::CPose3D(mrpt::poses::CPose2D(p)) + camera_on_robot;
            const double ahead = world.distanceAhead(cam.x(), cam.y(), p.phi + axis_yaw, cam.z());
            if (ahead < min_view_distance)
                throw core::UsageError(
                    "[" + trajectorySection(r) + "] waypoints: frame " + std::to_string(k) +
                    format(" at (%.2f, %.2f): the camera faces an obstacle %.2f m ahead", p.x, p.y,
                           ahead) +
                    " (< [Robots] min_view_distance)");
        }
    }
}

TSimulationSummary OfficeTeamScenario::run(const TSimulationOptions& options)
{
    const int robots = options.robots < 0 ? kDefaultRobots : options.robots;
    if (robots < 2 || robots > static_cast<int>(trajectories.size()))
        throw core::UsageError(name() + ": --robots must be 2 to " +
                               std::to_string(trajectories.size()) +
                               " (one [Trajectory_R<n>] section per robot)");
    const int n = options.frames < 0 ? trajectories.front().frames : options.frames;
    if (n <= 0) throw core::UsageError("the number of frames must be > 0");
    const size_t K = static_cast<size_t>(robots);
    const std::vector<std::vector<mrpt::math::TPose2D>> truth = paths(robots, n);
    const TOfficeModel model = world.build(textures);

    // Independent random streams per robot (RandomStreams.h: robot n uses index n).
    std::vector<OdometrySimulator> odo(K, odometry);
    std::vector<StereoRenderer> cams(K, stereo);
    for (size_t r = 0; r < K; r++) {
        const uint32_t index = static_cast<uint32_t>(r + 1);
        odo[r].reset(deriveStreamSeed(options.seed, RandomStream::Odometry, index));
        cams[r].reset(deriveStreamSeed(options.seed, RandomStream::ImageNoise, index));
    }

    // Files of robots an earlier, larger run had would otherwise stay beside the new ones.
    std::vector<std::string> image_labels;
    for (size_t r = 0; r < trajectories.size(); r++) {
        image_labels.push_back(label(r, "STEREO"));
        if (r < K) continue;
        for (const std::string kind : {".groundtruth_", ".odometry_"})
            std::filesystem::remove(options.out_prefix + kind + robotName(r) + ".tum");
    }
    DatasetWriter writer(options.out_prefix, options.write_images, image_labels,
                         TPngCoding::HuffmanOnly);
    std::vector<DeadReckoning> tracks;
    for (size_t r = 0; r < K; r++) tracks.emplace_back(mrpt::poses::CPose2D(truth[r].front()));

    m_statistics = TTeamStatistics();
    m_statistics.corners = model.corners.size();
    // Per robot and corner: frames seen in a row up to the last frame, and the best run.
    std::vector<std::vector<int>> run_length(K, std::vector<int>(model.corners.size(), 0));
    std::vector<std::vector<int>> best_run = run_length;

    const double period = trajectories.front().frame_period;
    for (int k = 0; k < n; k++) {
        const double t = start_time + k * period;
        const mrpt::Clock::time_point stamp = mrpt::Clock::fromDouble(t);
        for (size_t r = 0; r < K; r++) {
            const mrpt::poses::CPose2D robot(truth[r][static_cast<size_t>(k)]);
            tracks[r].step(t, robot, odo[r]);
            writer.writeObservation(
                *makeOdometryObservation(label(r, "ODOM"), tracks[r].odometryPose(), stamp));

            const mrpt::poses::CPose3D robot_in_world(robot);
            const mrpt::poses::CPose3D left_in_world = robot_in_world + camera_on_robot;
            if (options.write_images) {
                const auto [left, right] = cams[r].render(model.scene, left_in_world);
                const std::string stereo_label = label(r, "STEREO");
                const std::string left_file = DatasetWriter::imageFileName(stereo_label, k, "_L");
                const std::string right_file = DatasetWriter::imageFileName(stereo_label, k, "_R");
                writer.writeImage(left, left_file);
                writer.writeImage(right, right_file);
                writer.writeObservation(*makeStereoObservation(stereo_label, left_file, right_file,
                                                               stereo.stereoCamera(),
                                                               camera_on_robot, stamp));
            }
            writer.writeObservation(
                *makeGroundTruthObservation(robot_in_world, stamp, label(r, "GROUND_TRUTH")));

            for (size_t c = 0; c < model.corners.size(); c++) {
                int& run = run_length[r][c];
                run = stereo.seesPoint(model.scene, left_in_world, model.corners[c].position,
                                       kSeenMarginPx)
                          ? run + 1
                          : 0;
                best_run[r][c] = std::max(best_run[r][c], run);
            }
        }
        if (options.on_progress) options.on_progress(k + 1, n);
    }

    std::vector<TTumFile> tum;
    for (size_t r = 0; r < K; r++) {
        tum.push_back({"groundtruth_" + robotName(r), tracks[r].ground_truth,
                       "ground truth of " + robotName(r) +
                           ": robot base pose in the world (timestamp x y z qx qy qz qw)"});
        tum.push_back({"odometry_" + robotName(r), tracks[r].odometry,
                       "dead reckoning of the noisy odometry of " + robotName(r) +
                           " from its true initial pose"});
    }
    const core::LandmarkFile landmarks = model.cornerLandmarks();
    writer.writeImageBesideRawlog(drawOfficeTopView(world, model, truth), "topview");
    writer.commit(tum, landmarks,
                  "designed texture corners of the office world (ground-truth landmarks) [m]");

    countCorners(best_run);
    TSimulationSummary summary;
    summary.frames = n;
    summary.robots = robots;
    std::string seen, tracked;
    for (size_t r = 0; r < K; r++) {
        m_statistics.path_length.push_back(tracks[r].path_length);
        summary.path_length += tracks[r].path_length;
        const std::string sep = r ? ", " : "";
        seen += sep + robotName(r) + " " + std::to_string(m_statistics.seen[r]);
        tracked += sep + std::to_string(m_statistics.tracked[r]);
    }
    summary.details = std::to_string(m_statistics.corners) + " ground-truth corners, seen by " +
                      seen + " (in 3 frames in a row: " + tracked + "; by two robots or more: " +
                      std::to_string(m_statistics.tracked_by_several) + ")";
    return summary;
}

void OfficeTeamScenario::countCorners(const std::vector<std::vector<int>>& best_run)
{
    const size_t robots = best_run.size();
    m_statistics.seen.assign(robots, 0);
    m_statistics.tracked.assign(robots, 0);
    m_statistics.tracked_by_several = 0;
    for (size_t c = 0; c < m_statistics.corners; c++) {
        int trackers = 0;
        for (size_t r = 0; r < robots; r++) {
            m_statistics.seen[r] += best_run[r][c] >= 1;
            m_statistics.tracked[r] += best_run[r][c] >= kTrackedFrames;
            trackers += best_run[r][c] >= kTrackedFrames;
        }
        m_statistics.tracked_by_several += trackers >= 2;
    }
}

}  // namespace mrpt_vslam::sim
