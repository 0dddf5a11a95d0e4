#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/img/CImage.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/sim/DetectionSimulator.h>
#include <mrpt_vslam/sim/PajdlaBaksteinInverse.h>

namespace mrpt_vslam::sim {

/** Renders the 8-bit IR fisheye image of one frame (Gamallo et al. 2013, Sec. IV, Fig. 5a): dark
 *  background, ceiling lights as bright saturated blobs, spurious reflections, sparse noise.
 *
 *  1. Each light disk is rendered by inverse mapping: every pixel of its bounding box is split
 *     into `supersampling`² sub-pixels, each sub-pixel's ray (inverse of Eq. 1) is intersected
 *     with the disk's plane, and the pixel gets the covered fraction. Spurious spots are disks
 *     in image space, rendered the same way.
 *  2. Optics blur: Gaussian of `blur_sigma_px`; then value = 255·min(1, gain·coverage), so the
 *     centre saturates and the edges are soft; plus N(0, blob_noise_std²) on lit pixels.
 *  3. Sensor noise, kept sparse so PNG stays small: a fraction `noise_pixel_fraction` of the
 *     pixels inside the image circle gets a dark level in [1, noise_max_level], and a fraction
 *     `hot_pixel_fraction` a hot level in [hot_pixel_min, 255]. Everything else is exactly 0. */
class LightBlobRenderer : public mrpt::config::CLoadableOptions {
  public:
    /// @name Parameters (ini section [Image])
    /// @{
    int supersampling = 5;        ///< [-] sub-pixels per pixel side
    double blur_sigma_px = 0.7;   ///< [px] std of the optics blur
    double gain = 2.0;            ///< [-] coverage → brightness gain (≥ 1 saturates the core)
    double blob_noise_std = 3.0;  ///< [0-255] noise std on lit pixels
    double noise_pixel_fraction = 0.004;  ///< [-] fraction of dark-noise pixels
    int noise_max_level = 6;              ///< [0-255] highest dark-noise level
    double hot_pixel_fraction = 0.0002;   ///< [-] fraction of hot pixels
    int hot_pixel_min = 60;               ///< [0-255] lowest hot-pixel level
    /// @}

    void reset(uint32_t seed) { m_rng.randomize(seed); }

    /** The image of one frame. \param light_radius [m] radius of the light disks */
    mrpt::img::CImage render(const TFrameDetections& frame, double light_radius,
                             const PajdlaBaksteinInverse& model);

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                            const std::string& section) override;

  private:
    mrpt::random::CRandomGenerator m_rng;
};

}  // namespace mrpt_vslam::sim
