#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/img/CImage.h>
#include <mrpt/img/TStereoCamera.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/sim/TexturedScene.h>

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace mrpt_vslam::sim {

/** One noise-free rendered view. */
struct TRenderedView {
    int width = 0, height = 0;
    std::vector<float> radiance;  ///< [0-255] mean of the pixel's sub-samples, row-major
    std::vector<int> face;        ///< rectangle seen by the pixel's first sub-sample; −1: none
};

/** The 8-bit image of `view`: each pixel's radiance plus N(0, noise_std²) noise drawn from `rng`
 *  in row-major order (no draws when noise_std = 0), rounded and saturated. */
mrpt::img::CImage addPixelNoise(const TRenderedView& view, double noise_std,
                                mrpt::random::CRandomGenerator& rng);

/** A rectified stereo head (Gil et al. 2010, Sec. 6: Videre STH-MDCS2) and the renderer of its
 *  images.
 *
 *  Both cameras are ideal pinholes with the same intrinsics (fx, fy, cx, cy; no distortion), in
 *  MRPT's camera frame (x right, y down, z forward); the right camera sits at (baseline, 0, 0) in
 *  the left camera's frame, so a point at depth Z appears fx·baseline/Z pixels further left in
 *  the right image, on the same row. Pixel (col, row) is centred at u = col, v = row.
 *
 *  Rendering is exact for the pinhole model: every pixel is split into `supersampling`² sub-pixels
 *  whose rays are intersected with the scene's rectangles (each rectangle is projected first to
 *  bound the sub-pixels it can cover; a depth buffer keeps the nearest hit); each hit samples the
 *  face's texture with trilinear mipmapping (footprint z/(f·√|n·r|) per sub-pixel, r the ray with
 *  r_z = 1), and the pixel is the mean of its sub-samples, `background` where nothing is hit.
 *  Then additive N(0, noise_std²) noise per pixel, rounded to 8 bits. */
class StereoRenderer : public mrpt::config::CLoadableOptions {
  public:
    /// @name Parameters (ini section [StereoCamera])
    /// @{
    int width = 320, height = 240;  ///< [px] image size
    double fx = 280, fy = 280;      ///< [px] focal lengths
    double cx = 159.5, cy = 119.5;  ///< [px] principal point
    double baseline = 0.12;         ///< [m] distance between the optical centres
    int supersampling = 2;          ///< [-] sub-pixels per pixel side
    double noise_std = 0.8;         ///< [0-255] std of the additive pixel noise
    double background = 128;        ///< [0-255] value where no face is hit
    /// @}

    /// Seeds the pixel-noise generator.
    void reset(uint32_t seed) { m_rng.randomize(seed); }

    /// Intrinsics of either camera (rectified: no distortion).
    mrpt::img::TCamera camera() const;
    /// Both cameras and the left-to-right pose, as stored in CObservationStereoImages.
    mrpt::img::TStereoCamera stereoCamera() const;
    /// Pose of the right camera in the left camera's frame: (baseline, 0, 0), no rotation.
    mrpt::poses::CPose3D rightCameraInLeft() const { return {baseline, 0, 0, 0, 0, 0}; }
    /// [deg] horizontal and vertical field of view.
    Eigen::Vector2d fieldOfViewDeg() const;

    /// Pixel (u, v) of a point given in the camera frame (z > 0).
    Eigen::Vector2d project(const Eigen::Vector3d& p_camera) const
    {
        return {cx + fx * p_camera.x() / p_camera.z(), cy + fy * p_camera.y() / p_camera.z()};
    }

    /// The noise-free view of one camera at `camera_in_world`.
    TRenderedView renderView(const TexturedScene& scene,
                             const mrpt::poses::CPose3D& camera_in_world) const;

    /// Left and right 8-bit images, with noise, of the head whose left camera is at
    /// `left_in_world`.
    std::pair<mrpt::img::CImage, mrpt::img::CImage> render(
        const TexturedScene& scene, const mrpt::poses::CPose3D& left_in_world);

    /** Whether both cameras see `point`: in front of them, projected at least `margin_px`
     *  inside both images, and not hidden by any face. */
    bool seesPoint(const TexturedScene& scene, const mrpt::poses::CPose3D& left_in_world,
                   const Eigen::Vector3d& point, double margin_px) const;

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                            const std::string& section) override;

  private:
    mrpt::random::CRandomGenerator m_rng;
};

}  // namespace mrpt_vslam::sim
