#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt_vslam/core/FastHessianDetector.h>
#include <mrpt_vslam/core/IntegralImage.h>
#include <mrpt_vslam/core/ParallelFor.h>
#include <mrpt_vslam/core/USurfDescriptor.h>
#include <mrpt_vslam/core/UnifiedSphereCamera.h>
#include <mrpt_vslam/viewmap/ViewFeatures.h>

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

namespace mrpt::img {
class CImage;
}

namespace mrpt_vslam::viewmap {

/** SURF-like feature points of an omnidirectional image (doc/view-slam.md §4.1, §4 step 2;
 *  the paper uses SURF): the fast-Hessian detector (core::FastHessianDetector) on the image as
 *  it is, each point lifted to its unit ray by the central camera model and turned into the
 *  robot frame, with a SURF descriptor whose orientation is the image of the vertical.
 *
 *  Orientation [ours]: a turn of the robot about its vertical axis turns the omni image about the
 *  image of the zenith, so upright SURF (core::USurfDescriptor, axes of the image) no longer
 *  matches once the headings differ by more than ~15°: measured on rendered pairs, random
 *  headings leave a handful of matches. SURF's own orientation assignment (Bay et al. 2008,
 *  Sec. 4.1) would estimate the angle from the patch; here the geometry gives it exactly: the
 *  descriptor's "down" axis is the image direction, at the point, of the robot's −z (for our
 *  upward camera: radially outwards). The descriptor is then invariant to the robot's heading,
 *  and on an upright perspective image it is U-SURF (orientedDescriptor()).
 *
 *  extract():
 *   1. fast-Hessian keypoints of the 8-bit grayscale image (colour is converted);
 *   2. strongest first (response det H, ties by row, column, scale: a deterministic order);
 *   3. a point is kept when its pixel unprojects (inside the image circle of max_theta), the
 *      corners of its descriptor window shrunk by window_margin unproject too [ours: the black
 *      outside of the circle is the same in every image, so windows that see it match each
 *      other whatever the motion], and it has a descriptor;
 *   4. the first max_features kept points, rays turned by camera_to_robot.
 *
 *  Usage: `OmniFeatureExtractor fx(camera, Eigen::Matrix3d::Identity(), opts);
 *          const TViewFeatures f = fx.extract(image);`
 */
class OmniFeatureExtractor {
  public:
    /// Parameters, all read from one ini section (keys = member names).
    struct TOptions : public mrpt::config::CLoadableOptions {
        /** Fast-Hessian keys hessian_threshold, octaves, initial_step. Defaults [ours, measured
         *  on 100 rendered 640 × 480 omni-views pairs]: threshold 10, 3 octaves, step 2, i.e.
         *  about 650 points of which the 400 strongest are kept. Threshold 15 / 20 / 30 keep
         *  370 / 330 / 270 points and 5 / 14 / 26 % fewer inliers; step 1 gives 4 % more
         *  inliers for four times the detection time (about 25 ms against 7 ms); a fourth
         *  octave brings no more inliers (the windows of its points rarely fit in the circle). */
        core::FastHessianDetector::TOptions detector = defaultDetector();
        int max_features = 400;  ///< the strongest points kept, ≥ 1
        /** [-] part of the descriptor's half window (10.5 s) whose corners must lie inside the
         *  image circle: 1 keeps the whole window inside, 0 only the keypoint. */
        double window_margin = 0.5;

        /// Throws std::invalid_argument naming the ini key of a bad value.
        void validate() const;
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;

        static core::FastHessianDetector::TOptions defaultDetector();
    };

    /** \param camera model of the images (its width × height is checked by extract())
     *  \param camera_to_robot rotation of camera-frame rays into the robot frame (x forward, z up)
     *  \throw std::invalid_argument for invalid options or camera, or if camera_to_robot is not
     *  a rotation */
    OmniFeatureExtractor(const core::UnifiedSphereCamera& camera,
                         const Eigen::Matrix3d& camera_to_robot, const TOptions& options);

    /** Feature points of `image`, strongest first.
     *  \throw std::invalid_argument if the image size differs from the camera's, or the image is
     *  empty or not 8-bit. */
    TViewFeatures extract(const mrpt::img::CImage& image) const;

    /** SURF descriptor (Bay et al. 2008, Sec. 4.1, the layout of core::USurfDescriptor) of the
     *  keypoint (x, y) at scale s, with its axes turned: the sample grid and the Haar responses
     *  are taken along u = (down.y, −down.x) and v = down (unit, image coordinates). The Haar
     *  boxes stay aligned with the image (exact sub-pixel integrals); down = (0, 1) gives U-SURF.
     *  \return nullopt when a Haar box would leave the image, or on a flat patch. */
    static std::optional<core::USurfDescriptor::TDescriptor> orientedDescriptor(
        const core::IntegralImage& integral, double x, double y, double s,
        const Eigen::Vector2d& down);

    /** The summed-area table as doubles, for inline sub-pixel integrals (the values of
     *  core::IntegralImage::integralAt): the oriented descriptor needs 3200 of them per point,
     *  which this makes about three times faster. */
    struct TIntegralTable {
        explicit TIntegralTable(const core::IntegralImage& integral);
        /// Integral over [−½, x) × [−½, y), bilinear in the table; −½ ≤ x < width − ½, same for y.
        double at(double x, double y) const
        {
            const double tx = x + 0.5, ty = y + 0.5;
            const size_t i = size_t(tx), j = size_t(ty);
            const double fx = tx - double(i), fy = ty - double(j);
            const double* t0 = &values[j * stride + i];
            const double* t1 = t0 + stride;
            const double top = t0[0] + fx * (t0[1] - t0[0]);
            return top + fy * (t1[0] + fx * (t1[1] - t1[0]) - top);
        }
        int width, height;
        size_t stride;
        std::vector<double> values;  ///< (height + 1) × (width + 1), row-major
    };
    /// orientedDescriptor() on a table built once per image.
    static std::optional<core::USurfDescriptor::TDescriptor> orientedDescriptor(
        const TIntegralTable& table, double x, double y, double s, const Eigen::Vector2d& down);

    const TOptions& options() const { return m_options; }
    const core::UnifiedSphereCamera& camera() const { return m_camera; }
    /// The model of the next images. \throw std::invalid_argument if it is not valid.
    void setCamera(const core::UnifiedSphereCamera& camera);
    /// The rotation from the camera frame to the robot frame.
    const Eigen::Matrix3d& cameraToRobot() const { return m_camera_to_robot; }
    /// \throw std::invalid_argument if `camera_to_robot` is not a rotation matrix.
    void setCameraToRobot(const Eigen::Matrix3d& camera_to_robot);
    /// Threads extract() runs on (0: every core; default 1); the features do not depend on it.
    void setThreadCount(unsigned threads) { m_threads = core::resolveThreadCount(threads); }

  private:
    /// A keypoint's feature: its ray in the camera frame and descriptor, if it has one.
    struct TDescribed {
        Eigen::Vector3d ray;
        core::USurfDescriptor::TDescriptor descriptor;
    };
    std::optional<TDescribed> describe(const core::FastHessianDetector::TKeypoint& kp,
                                       const TIntegralTable& table) const;

    core::UnifiedSphereCamera m_camera;
    Eigen::Matrix3d m_camera_to_robot;
    TOptions m_options;
    core::FastHessianDetector m_detector;
    unsigned m_threads = 1;
};

}  // namespace mrpt_vslam::viewmap
