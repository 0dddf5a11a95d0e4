#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPose3DQuat.h>
#include <mrpt_vslam/multirobot/StereoRectifier.h>

#include <stdexcept>
#include <string>

namespace mrpt_vslam::multirobot {

namespace {

bool sameCalibration(const mrpt::img::TStereoCamera& a, const mrpt::img::TStereoCamera& b)
{
    return a.leftCamera == b.leftCamera && a.rightCamera == b.rightCamera &&
           mrpt::poses::CPose3DQuat(a.rightCameraPose) ==
               mrpt::poses::CPose3DQuat(b.rightCameraPose);
}

}  // namespace

mrpt::obs::CObservationStereoImages StereoRectifier::rectify(
    const mrpt::obs::CObservationStereoImages& obs)
{
    mrpt::img::TStereoCamera params;
    obs.getStereoCameraParams(params);
    const auto& left = params.leftCamera;
    const auto& right = params.rightCamera;
    if (left.ncols != right.ncols || left.nrows != right.nrows)
        throw std::invalid_argument(
            "the left and right cameras are calibrated for images of "
            "different sizes");
    if (!m_map.isSet() || !sameCalibration(params, m_map.getCameraParams())) {
        m_map.setAlpha(0);
        m_map.setFromCamParams(params);
    }

    mrpt::obs::CObservationStereoImages out;
    out.timestamp = obs.timestamp;
    out.sensorLabel = obs.sensorLabel;
    out.hasImageRight = true;
    m_map.rectify(obs.imageLeft, obs.imageRight, out.imageLeft, out.imageRight);
    mrpt::img::TStereoCamera rectified = m_map.getRectifiedImageParams();
    const mrpt::poses::CPose3D right_in_left(params.rightCameraPose);
    rectified.rightCameraPose =
        mrpt::math::TPose3DQuat(right_in_left.translation().norm(), 0, 0, 1, 0, 0, 0);
    out.setStereoCameraParams(rectified);
    // the rectified left camera: the stated one turned by R1ᵀ
    out.cameraPose = mrpt::poses::CPose3DQuat(mrpt::poses::CPose3D(obs.cameraPose) +
                                              -mrpt::poses::CPose3D(m_map.getLeftCameraRot()));
    return out;
}

}  // namespace mrpt_vslam::multirobot
