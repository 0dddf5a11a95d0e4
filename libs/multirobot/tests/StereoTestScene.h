#pragma once
// Synthetic rectified stereo pairs of a textured plane, rendered through the exact plane
// homographies, for the front-end tests.

#include <mrpt/img/CImage.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/poses/CPose3D.h>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

namespace mrpt_vslam::multirobot::test {

/** A cluttered texture: smooth random shading at two scales with random rectangles and
 *  ellipses of random gray levels on top, slightly blurred (no aliasing when rendered at about
 *  one texel per pixel). Deterministic for a given seed. */
inline cv::Mat makeTexture(int width, int height, uint64_t seed)
{
    cv::RNG rng(seed);
    cv::Mat tex(height, width, CV_32F, cv::Scalar(0));
    for (const int cell : {32, 6}) {
        cv::Mat coarse(height / cell + 2, width / cell + 2, CV_32F), fine;
        rng.fill(coarse, cv::RNG::UNIFORM, -1, 1);
        cv::resize(coarse, fine, cv::Size(coarse.cols * cell, coarse.rows * cell), 0, 0,
                   cv::INTER_CUBIC);
        tex += (cell > 10 ? 60.0f : 25.0f) * fine(cv::Rect(0, 0, width, height));
    }
    tex += 128;
    for (int i = 0; i < width * height / 500; i++) {
        const cv::Point c(rng.uniform(0, width), rng.uniform(0, height));
        const cv::Size half(rng.uniform(2, 16), rng.uniform(2, 16));
        const cv::Scalar gray(rng.uniform(0, 256));
        if (rng.uniform(0, 2) == 0)
            cv::rectangle(tex, c - cv::Point(half.width, half.height),
                          c + cv::Point(half.width, half.height), gray, cv::FILLED);
        else
            cv::ellipse(tex, c, half, rng.uniform(0.0, 180.0), 0, 360, gray, cv::FILLED);
    }
    cv::GaussianBlur(tex, tex, cv::Size(0, 0), 1.0);
    cv::Mat out;
    tex.convertTo(out, CV_8U);
    return out;
}

/** A textured plane seen by a rectified stereo pair that translates without rotating.
 *  World frame = the left camera frame at position 0 (x right, y down, z forward); texel
 *  (u, v) lies at P(u, v) = origin + u·e1 + v·e2. */
struct TPlaneScene {
    int width = 320, height = 240;
    double fx = 400, fy = 400, cx = 159.5, cy = 119.5;
    double baseline = 0.12;  ///< [m]
    cv::Mat texture;
    Eigen::Vector3d origin, e1, e2;

    /** A plane through (0, 0, depth), turned by `yaw` about the camera's y axis (0: fronto-
     *  parallel), texels of `texel` metres, centred on the optical axis. */
    static TPlaneScene plane(double depth, double yaw, double texel = 0.005, uint64_t seed = 7)
    {
        TPlaneScene s;
        s.texture = makeTexture(1400, 1000, seed);
        s.e1 = texel * Eigen::Vector3d(std::cos(yaw), 0, std::sin(yaw));
        s.e2 = texel * Eigen::Vector3d(0, 1, 0);
        s.origin = Eigen::Vector3d(0, 0, depth) - 700 * s.e1 - 500 * s.e2;
        return s;
    }

    Eigen::Matrix3d K() const
    {
        Eigen::Matrix3d k;
        k << fx, 0, cx, 0, fy, cy, 0, 0, 1;
        return k;
    }

    /// Image of a camera at `position` (world frame, no rotation): x ~ K [e1 e2 origin − t].
    cv::Mat render(const Eigen::Vector3d& position) const
    {
        Eigen::Matrix3d M;
        M << e1, e2, origin - position;
        const Eigen::Matrix3d H = K() * M;
        cv::Mat h(3, 3, CV_64F);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) h.at<double>(r, c) = H(r, c);
        cv::Mat img;
        cv::warpPerspective(texture, img, h, cv::Size(width, height), cv::INTER_LINEAR,
                            cv::BORDER_CONSTANT, cv::Scalar(128));
        return img;
    }

    /// The point of the plane seen at left pixel (row, col) of the camera at `position`, in
    /// that camera's frame.
    Eigen::Vector3d pointAt(double row, double col, const Eigen::Vector3d& position) const
    {
        const Eigen::Vector3d ray((col - cx) / fx, (row - cy) / fy, 1);
        const Eigen::Vector3d n = e1.cross(e2);
        return ray * (n.dot(origin - position) / n.dot(ray));
    }

    /// Left and right images of the pair whose left camera is at `left_position`, with
    /// Gaussian pixel noise of `noise_std` gray levels (seeded).
    mrpt::obs::CObservationStereoImages::Ptr stereo(const Eigen::Vector3d& left_position,
                                                    double noise_std = 2.0, uint64_t seed = 1) const
    {
        cv::RNG rng(seed);
        const auto noisy = [&](const cv::Mat& img) {
            cv::Mat n(img.size(), CV_32F), out;
            rng.fill(n, cv::RNG::NORMAL, 0, noise_std);
            img.convertTo(out, CV_32F);
            out += n;
            out.convertTo(out, CV_8U);  // rounds and saturates
            return out;
        };
        auto obs = mrpt::obs::CObservationStereoImages::Create();
        obs->sensorLabel = "R1_STEREO";
        obs->timestamp = mrpt::Clock::fromDouble(1000.0 + left_position.x());
        obs->imageLeft = mrpt::img::CImage(noisy(render(left_position)), mrpt::img::DEEP_COPY);
        obs->imageRight = mrpt::img::CImage(
            noisy(render(left_position + Eigen::Vector3d(baseline, 0, 0))), mrpt::img::DEEP_COPY);
        obs->hasImageRight = true;
        mrpt::img::TStereoCamera params;
        params.leftCamera.ncols = params.rightCamera.ncols = width;
        params.leftCamera.nrows = params.rightCamera.nrows = height;
        params.leftCamera.setIntrinsicParamsFromValues(fx, fy, cx, cy);
        params.rightCamera = params.leftCamera;
        params.rightCameraPose = mrpt::math::TPose3DQuat(baseline, 0, 0, 1, 0, 0, 0);
        obs->setStereoCameraParams(params);
        // Camera looking forward along the robot's x axis, 0.5 m above the base.
        obs->cameraPose =
            mrpt::poses::CPose3DQuat(mrpt::poses::CPose3D(0.1, 0, 0.5, -M_PI / 2, 0, -M_PI / 2));
        return obs;
    }
};

}  // namespace mrpt_vslam::multirobot::test
