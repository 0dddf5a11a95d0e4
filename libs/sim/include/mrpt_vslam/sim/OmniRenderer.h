#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/img/CImage.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/UnifiedSphereCamera.h>
#include <mrpt_vslam/sim/StereoRenderer.h>
#include <mrpt_vslam/sim/TexturedScene.h>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace mrpt_vslam::sim {

/** Renders the 8-bit grayscale image of a central omnidirectional camera (unified sphere model,
 *  core::UnifiedSphereCamera) in a TexturedScene by ray casting.
 *
 *  Per pixel (u, v) (pixel centres at integer coordinates, one ray per pixel):
 *  1. its unit ray r in the camera frame (z = optical axis) from UnifiedSphereCamera::unproject,
 *     turned into the world;
 *  2. the nearest rectangle the ray crosses (TexturedRectangle::intersect), at distance λ;
 *  3. that face's texture at the hit point (TexturedRectangle::sample: bilinear, blended
 *     between mipmap levels) for the footprint ppm·λ·δ/√|n·r| texels, where δ [rad] is the angle
 *     the pixel spans, (det J·Jᵀ)^(−1/4) with J = ∂(u, v)/∂X of the model at r, and n·r the
 *     cosine of incidence (as StereoRenderer's footprint for a pinhole);
 *  4. additive N(0, noise_std²) noise, rounded to 8 bits (addPixelNoise).
 *  Pixels outside the model's valid area (outside the image circle of max_theta) or whose ray
 *  hits nothing are 0.
 *
 *  Each face is bounded by the cone its circumscribed sphere subtends at the camera, so a ray
 *  only tests the faces whose cone holds it. Rays and pixel angles are tabulated by
 *  setCamera(). */
class OmniRenderer : public mrpt::config::CLoadableOptions {
  public:
    /// @name Parameters (the camera keys of core::UnifiedSphereCamera plus noise_std)
    /// @{
    double noise_std = 1.0;  ///< [0-255] std of the additive pixel noise
    /// @}

    OmniRenderer() { setCamera(core::UnifiedSphereCamera()); }

    /// The camera model.
    const core::UnifiedSphereCamera& camera() const { return m_camera; }
    /// Sets the camera model and tabulates the ray and the angle of every pixel.
    void setCamera(const core::UnifiedSphereCamera& camera);

    /// Seeds the pixel-noise generator.
    void reset(uint32_t seed) { m_rng.randomize(seed); }

    /** The noise-free view from `camera_in_world` (camera frame as in core::UnifiedSphereCamera):
     *  radiance [0-255] and face index per pixel; −1 (radiance 0) outside the valid area or where
     *  the ray hits nothing. */
    TRenderedView renderView(const TexturedScene& scene,
                             const mrpt::poses::CPose3D& camera_in_world) const;

    /// The 8-bit image, with noise, from `camera_in_world`.
    mrpt::img::CImage render(const TexturedScene& scene,
                             const mrpt::poses::CPose3D& camera_in_world);

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                            const std::string& section) override;

  private:
    core::UnifiedSphereCamera m_camera;
    std::vector<Eigen::Vector3d> m_rays;  ///< per pixel, unit, camera frame; 0 if not valid
    std::vector<double> m_pixel_angle;    ///< [rad] δ per pixel; 0 if not valid
    mrpt::random::CRandomGenerator m_rng;
};

}  // namespace mrpt_vslam::sim
