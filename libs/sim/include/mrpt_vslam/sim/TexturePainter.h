#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/img/CImage.h>
#include <mrpt/random/RandomGenerators.h>

#include <Eigen/Core>
#include <vector>

namespace mrpt_vslam::sim {

/** What a face of the world looks like. */
enum class TSurfaceKind {
    Wall,     ///< room wall or partition: posters, checkerboards, doors on a plain background
    Cabinet,  ///< cabinet front: doors and drawers of different grays with handles
    Shelf,    ///< bookshelf front: boards, dark compartments, books
    Desk,     ///< desk front: top board, drawer pedestal, dark knee space
    Panel,    ///< plain low-contrast surface (sides and tops of furniture), no corners
    Floor,    ///< plain darker surface, no corners
    Ceiling   ///< plain lighter surface, no corners
};

/** A span [s0, s1] [m] along a wall face, from the floor up to `top` [m]. */
struct TWallSpan {
    double s0 = 0, s1 = 0;
    double top = 0;
};

/** The face to paint. The texture's t axis points down from the face's top edge. */
struct TFaceRequest {
    TSurfaceKind kind = TSurfaceKind::Panel;
    double width = 0, height = 0;       ///< [m]
    std::vector<TWallSpan> doors;       ///< Wall only: door openings to paint (top = door height)
    std::vector<TWallSpan> keep_clear;  ///< Wall only: spans hidden by furniture up to `top`
};

/** A painted texture and its designed corners. */
struct TPaintedTexture {
    mrpt::img::CImage image;               ///< 8-bit grayscale
    double pixels_per_metre = 0;           ///< [texel/m]
    std::vector<Eigen::Vector2d> corners;  ///< [m] face coordinates (s, t) of the kept corners
};

/** Paints procedural grayscale textures of an office and knows where their corners are.
 *
 *  Every shape is a polygon filled with a flat gray over a low-contrast background (a base gray,
 *  smooth blotches and fine noise); its vertices are the *designed corners*. Axis-aligned
 *  rectangles are snapped to the texel grid, so their edges and corners are exact; other polygons
 *  are filled with 4×4 supersampled coverage. A designed corner is kept only when a corner
 *  detector can find it in the final texture: inside the face by more than `corner_window`, an
 *  equivalent contrast √(2·λ_min/w) ≥ `min_corner_contrast`, where λ_min is the smaller
 *  eigenvalue of the gradient structure tensor over the 2w × 2w texels around it (w =
 *  corner_window in texels; an ideal right-angle corner of contrast c gives c, a straight edge or
 *  a corner covered by a later shape gives about the noise), and no other kept corner within
 *  `min_corner_separation` (both go). Posters overlap their shapes on purpose; checkerboards give
 *  repetitive corners on purpose (Gil et al. 2010, Sec. 5: data association among similar
 *  landmarks). */
class TexturePainter : public mrpt::config::CLoadableOptions {
  public:
    /// @name Parameters (ini section [Textures])
    /// @{
    double pixels_per_metre = 200;        ///< [texel/m] walls and furniture
    double floor_pixels_per_metre = 50;   ///< [texel/m] floor and ceiling
    double background_noise_std = 1.0;    ///< [0-255] fine noise of the backgrounds
    double background_blotch_std = 6.0;   ///< [0-255] smooth variation of the backgrounds
    double min_corner_contrast = 40;      ///< [0-255] equivalent contrast of a kept corner
    double corner_window = 0.04;          ///< [m] half size of the corner test window
    double min_corner_separation = 0.04;  ///< [m] kept corners are at least this far apart
    double item_gap_min = 0.3, item_gap_max = 1.0;  ///< [m] gap between items along a wall
    /// @}

    /// Paints one face; the same request and generator state give the same texture.
    TPaintedTexture paint(const TFaceRequest& face, mrpt::random::CRandomGenerator& rng) const;

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                            const std::string& section) override;
};

}  // namespace mrpt_vslam::sim
