#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt_vslam/core/PajdlaBaksteinCamera.h>

#include <cstddef>
#include <vector>

namespace mrpt_vslam::core {

/** Inverse of the fisheye model (PajdlaBaksteinCamera, Eq. 1) by look-up table, as built in
 *  Gamallo et al. (2013, Sec. III-A):
 *
 *   1. Sample φ ∈ [−π, π) and θ ∈ [0, max_theta] with steps δφ, δθ and project every sample with
 *      Eq. 1 to a pixel.
 *   2. Store for each pixel the minimum and maximum of the φ and θ values that fell into it.
 *
 *  A pixel (col, row) owns the square [col − ½, col + ½) × [row − ½, row + ½) (pixel centres at
 *  integer coordinates, as in MRPT and OpenCV). Each cell keeps the centre of the φ and θ ranges
 *  (the estimate) and their half-widths (the uncertainty) as floats.
 *
 *  Azimuth wrap-around: φ is accumulated as an offset from the azimuth of the pixel centre as seen
 *  from (u0, v0), wrapped to (−π, π], so a pixel on the −x half-axis (φ = ±π) gets a narrow range
 *  around ±π instead of one spanning 2π. The pixel that holds the image centre (θ = 0, where φ is
 *  undefined) is hit by every azimuth and reports a φ half-range of about π.
 *
 *  Coverage: with the automatic steps (options left at 0) neighbouring samples are at most ½ px
 *  apart, so every sampling cell lies within ½ px of one of its corners and every pixel whose
 *  centre lies inside the image circle r ≤ r(max_theta) is hit. Pixels no sample hits (outside
 *  the circle or the image, rim pixels whose centre is outside the circle, or holes left by
 *  coarse steps chosen by hand) are invalid; they are not filled from neighbours.
 *
 *  Usage:
 *   1. Load or set a PajdlaBaksteinCamera and, optionally, a TOptions (ini keys
 *      `lut_delta_phi_deg`, `lut_delta_theta_deg`).
 *   2. Build the table once: `FisheyeLookupTable lut(camera, options);`.
 *   3. For each feature centroid (u, v): `auto z = lut.lookup(u, v); if (z.valid) ...`.
 */
class FisheyeLookupTable {
  public:
    /** Sampling steps of the table. 0 (the default) picks the largest step that keeps
     *  neighbouring samples ≤ ½ px apart for the given camera. */
    struct TOptions : public mrpt::config::CLoadableOptions {
        double lut_delta_phi = 0;    ///< [rad] δφ, ini key `lut_delta_phi_deg` (0 = automatic)
        double lut_delta_theta = 0;  ///< [rad] δθ, ini key `lut_delta_theta_deg` (0 = automatic)

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
    };

    /// One pixel of the table; `phi` is NaN when no sample hit the pixel.
    struct TCell {
        float phi;               ///< [rad] centre of the φ range, in (−π, π]
        float phi_half_range;    ///< [rad] half-width of the φ range
        float theta;             ///< [rad] centre of the θ range
        float theta_half_range;  ///< [rad] half-width of the θ range
    };

    /// Result of a look-up: ray angles of the pixel and their uncertainty.
    struct TLookup {
        bool valid = false;           ///< false: outside the image or no sample hit the pixel
        double phi = 0;               ///< [rad] azimuth estimate (centre of the range)
        double theta = 0;             ///< [rad] angle from the optical axis (centre of the range)
        double phi_half_range = 0;    ///< [rad] half-width of the φ range of the pixel
        double theta_half_range = 0;  ///< [rad] half-width of the θ range of the pixel
    };

    /** Builds the table for `camera` (validated first) with the steps of `options`.
     *  \throw std::invalid_argument if a step is negative, NaN or larger than the sampled range,
     *  or if the steps would take more than kMaxSamples samples (a model that images the field of
     *  view far beyond any image). */
    FisheyeLookupTable(const PajdlaBaksteinCamera& camera, const TOptions& options);
    /// The most (φ, θ) samples a table is built from: over 300 times what the default camera
    /// (640 × 480) takes with the automatic steps.
    static constexpr double kMaxSamples = 5e8;
    /// Builds the table for `camera` with the automatic steps.
    explicit FisheyeLookupTable(const PajdlaBaksteinCamera& camera);

    /** Ray angles for a (sub-pixel) image point: the cell of the nearest pixel, i.e. the pixel
     *  whose square contains (u, v); no interpolation between cells.
     *  \param u column [px], \param v row [px]. */
    TLookup lookup(double u, double v) const;

    /// The stored cell of pixel (col, row); both must be inside the image.
    const TCell& cell(int col, int row) const;

    /// @name Table parameters
    /// @{
    const PajdlaBaksteinCamera& camera() const { return m_camera; }
    /// [rad] δφ actually used (the requested or automatic step, shrunk to divide 2π evenly).
    double deltaPhi() const { return m_delta_phi; }
    /// [rad] δθ actually used (shrunk to divide max_theta evenly).
    double deltaTheta() const { return m_delta_theta; }
    /// Number of pixels hit by at least one sample.
    size_t validPixelCount() const { return m_valid_pixels; }
    /// [bytes] memory held by the cells.
    size_t memoryBytes() const { return m_cells.size() * sizeof(TCell); }
    /// @}

  private:
    void build();

    PajdlaBaksteinCamera m_camera;
    double m_delta_phi = 0;
    double m_delta_theta = 0;
    size_t m_valid_pixels = 0;
    std::vector<TCell> m_cells;  ///< row-major, width × height
};

}  // namespace mrpt_vslam::core
