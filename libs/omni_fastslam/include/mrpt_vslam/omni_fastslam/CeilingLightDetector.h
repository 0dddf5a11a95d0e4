#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/img/CImage.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt_vslam/core/FisheyeLookupTable.h>
#include <mrpt_vslam/core/PajdlaBaksteinCamera.h>

#include <vector>

namespace mrpt_vslam::omni_fastslam {

/** Extracts ceiling-light measurements from an IR fisheye image (Gamallo et al. 2013, Sec. III-A):
 *
 *   1. threshold the 8-bit image (lights are the only bright objects behind the IR filter);
 *   2. connected components (OpenCV), blobs outside [min_blob_area, max_blob_area] rejected;
 *   3. intensity-weighted centroid (u_l, v_l) of each blob;
 *   4. (φ, θ) of the centroid through the look-up table inverse of Eq. 1, with covariance
 *      Q = J⁻¹ diag(σ_px²) J⁻ᵀ + diag(h_φ², h_θ²)/3, where J = ∂(u,v)/∂(φ,θ) and h the LUT
 *      half-ranges of the pixel (a uniform error inside the range has variance h²/3).
 *
 *  The output is the same `CObservationBearingRange` a rawlog carries as `OMNICAM_BEARINGS`
 *  (range = NaN, yaw = φ, pitch = θ − π/2 = −elevation, per-measurement covariances), so the
 *  filter has one input path for images and for pre-extracted bearings.
 */
class CeilingLightDetector {
  public:
    struct TOptions : public mrpt::config::CLoadableOptions {
        int intensity_threshold = 100;           ///< [0-255] pixels above it belong to a light
        int min_blob_area = 6;                   ///< [px] smaller blobs are noise
        int max_blob_area = 4000;                ///< [px] larger blobs are reflections / windows
        double pixel_std = 0.7;                  ///< [px] std of the blob centroid
        core::FisheyeLookupTable::TOptions lut;  ///< LUT sampling steps

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
    };

    /// A detected blob: centroid [px] and area [px].
    struct TBlob {
        double u = 0, v = 0;
        int area = 0;
    };

    /// Builds the look-up table once for `camera` (the camera's parameters are validated).
    CeilingLightDetector(const core::PajdlaBaksteinCamera& camera, const TOptions& options);

    /// Steps 1-3; a colour image is read as its grayscale (MRPT's conversion).
    /// \throw std::invalid_argument for an empty image or one that is not 8-bit.
    std::vector<TBlob> detectBlobs(const mrpt::img::CImage& image) const;

    /// Steps 1-4 on an `OMNICAM` observation; the output keeps its timestamp and camera pose
    /// and has label `sensor_label`. Blobs whose pixel has no LUT entry are dropped.
    /// \throw std::invalid_argument as detectBlobs(), or for an image of another size than the
    /// camera model's (core::requireImageSize).
    mrpt::obs::CObservationBearingRange::Ptr detect(
        const mrpt::obs::CObservationImage& obs,
        const std::string& sensor_label = "OMNICAM_BEARINGS") const;

    const core::FisheyeLookupTable& lookupTable() const { return m_lut; }

  private:
    TOptions m_options;
    core::FisheyeLookupTable m_lut;
};

}  // namespace mrpt_vslam::omni_fastslam
