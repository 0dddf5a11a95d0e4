#include <mrpt_vslam/sim/FrameObservations.h>

#include <cmath>
#include <limits>

namespace mrpt_vslam::sim {

mrpt::obs::CObservationImage::Ptr makeImageObservation(const std::string& image_file, int width,
                                                       int height,
                                                       const mrpt::poses::CPose3D& camera_on_robot,
                                                       mrpt::Clock::time_point stamp)
{
    auto obs = mrpt::obs::CObservationImage::Create();
    obs->sensorLabel = kImageLabel;
    obs->timestamp = stamp;
    obs->cameraPose = camera_on_robot;
    obs->cameraParams.ncols = static_cast<uint32_t>(width);
    obs->cameraParams.nrows = static_cast<uint32_t>(height);
    obs->image.setExternalStorage(image_file);
    return obs;
}

mrpt::obs::CObservationBearingRange::Ptr makeBearingObservation(
    const TFrameDetections& frame, const mrpt::poses::CPose3D& camera_on_robot,
    const std::function<Eigen::Vector2d(double theta)>& std_at_theta,
    const Eigen::Vector2d& angular_std, double max_theta, mrpt::Clock::time_point stamp)
{
    auto obs = mrpt::obs::CObservationBearingRange::Create();
    obs->sensorLabel = kBearingsLabel;
    obs->timestamp = stamp;
    obs->setSensorPose(camera_on_robot);
    obs->minSensorDistance = 0;
    obs->maxSensorDistance = 0;
    obs->fieldOfView_yaw = static_cast<float>(2 * M_PI);
    obs->fieldOfView_pitch = static_cast<float>(2 * max_theta);
    obs->validCovariances = true;
    obs->sensor_std_range = 0;
    obs->sensor_std_yaw = static_cast<float>(angular_std.x());
    obs->sensor_std_pitch = static_cast<float>(angular_std.y());
    for (const TBearing& b : frame.bearings) {
        mrpt::obs::CObservationBearingRange::TMeasurement m;
        m.range = std::numeric_limits<float>::quiet_NaN();
        m.yaw = static_cast<float>(b.phi);
        // elevation above the camera's horizontal plane = π/2 − θ; pitch = −elevation
        m.pitch = static_cast<float>(b.theta - M_PI / 2);
        m.landmarkID = -1;
        m.covariance.setZero();
        const Eigen::Vector2d std = std_at_theta(b.theta);
        m.covariance(1, 1) = std.x() * std.x();
        m.covariance(2, 2) = std.y() * std.y();
        obs->sensedData.push_back(m);
    }
    return obs;
}

mrpt::obs::CObservationRobotPose::Ptr makeGroundTruthObservation(
    const mrpt::poses::CPose3D& robot_in_world, mrpt::Clock::time_point stamp,
    const std::string& label)
{
    auto obs = mrpt::obs::CObservationRobotPose::Create();
    obs->sensorLabel = label;
    obs->timestamp = stamp;
    obs->pose.mean = robot_in_world;
    obs->pose.cov.setZero();
    return obs;
}

mrpt::obs::CObservationOdometry::Ptr makeOdometryObservation(const std::string& label,
                                                             const mrpt::poses::CPose2D& odometry,
                                                             mrpt::Clock::time_point stamp)
{
    auto obs = mrpt::obs::CObservationOdometry::Create();
    obs->sensorLabel = label;
    obs->timestamp = stamp;
    obs->odometry = odometry;
    return obs;
}

mrpt::obs::CObservationStereoImages::Ptr makeStereoObservation(
    const std::string& label, const std::string& left_file, const std::string& right_file,
    const mrpt::img::TStereoCamera& camera, const mrpt::poses::CPose3D& camera_on_robot,
    mrpt::Clock::time_point stamp)
{
    auto obs = mrpt::obs::CObservationStereoImages::Create();
    obs->sensorLabel = label;
    obs->timestamp = stamp;
    obs->setStereoCameraParams(camera);
    obs->cameraPose = mrpt::poses::CPose3DQuat(camera_on_robot);
    obs->imageLeft.setExternalStorage(left_file);
    obs->imageRight.setExternalStorage(right_file);
    obs->hasImageRight = true;
    obs->hasImageDisparity = false;
    return obs;
}

}  // namespace mrpt_vslam::sim
