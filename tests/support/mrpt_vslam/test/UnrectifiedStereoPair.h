#pragma once
// Stereo pairs of a head that is not rectified, made from a rectified pair, for the tests of
// the stereo front-end's rectification.

#include <mrpt/img/CImage.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPose3DQuat.h>

#include <Eigen/Core>
#include <opencv2/imgproc.hpp>

namespace mrpt_vslam::test {

/** The pair that a head with radial lens distortion (k1, k2; MRPT's dist[0], dist[1]) and its
 *  right camera turned by `turn` on its optical centre takes of the scene of the rectified pair
 *  `rectified`: each pixel of the new images is undistorted (fixed-point iteration), turned into
 *  the rectified camera's frame and read there (bilinear, grey outside), exact for a turn about
 *  the optical centre. The calibration says so; the camera pose is the rectified pair's. */
inline mrpt::obs::CObservationStereoImages unrectifiedPair(
    const mrpt::obs::CObservationStereoImages& rectified, double k1, double k2,
    const mrpt::poses::CPose3D& turn)
{
    const auto& cam = rectified.leftCamera;
    const auto warp = [&](const mrpt::img::CImage& image, const mrpt::math::CMatrixDouble33& R) {
        cv::Mat map(static_cast<int>(cam.nrows), static_cast<int>(cam.ncols), CV_32FC2);
        for (int r = 0; r < map.rows; r++)
            for (int c = 0; c < map.cols; c++) {
                const double xd = (c - cam.cx()) / cam.fx(), yd = (r - cam.cy()) / cam.fy();
                double x = xd, y = yd;
                for (int i = 0; i < 50; i++) {
                    const double r2 = x * x + y * y, f = 1 + k1 * r2 + k2 * r2 * r2;
                    x = xd / f;
                    y = yd / f;
                }
                const Eigen::Vector3d ray = R.asEigen() * Eigen::Vector3d(x, y, 1);
                map.at<cv::Vec2f>(r, c) = {
                    static_cast<float>(cam.cx() + cam.fx() * ray.x() / ray.z()),
                    static_cast<float>(cam.cy() + cam.fy() * ray.y() / ray.z())};
            }
        cv::Mat out;
        cv::remap(image.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY), out, map, cv::Mat(),
                  cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(128));
        return mrpt::img::CImage(out, mrpt::img::DEEP_COPY);
    };
    mrpt::obs::CObservationStereoImages obs;
    obs.timestamp = rectified.timestamp;
    obs.sensorLabel = rectified.sensorLabel;
    obs.cameraPose = rectified.cameraPose;
    obs.hasImageRight = true;
    obs.imageLeft = warp(rectified.imageLeft, mrpt::math::CMatrixDouble33::Identity());
    // the turned camera's rays in the rectified camera's frame
    obs.imageRight = warp(rectified.imageRight, turn.getRotationMatrix());
    auto params = rectified.getStereoCameraParams();
    for (auto* camera : {&params.leftCamera, &params.rightCamera}) {
        camera->dist.fill(0);
        camera->dist[0] = k1;
        camera->dist[1] = k2;
    }
    const double baseline = rectified.rightCameraPose.x();
    params.rightCameraPose =
        mrpt::poses::CPose3DQuat(mrpt::poses::CPose3D(baseline, 0, 0) + turn).asTPose();
    obs.setStereoCameraParams(params);
    return obs;
}

}  // namespace mrpt_vslam::test
