#pragma once

#include <mrpt/img/CImage.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

namespace mrpt_vslam::sim {

/** A planar rectangle of a world with a grayscale texture.
 *
 *  Its points are origin + s·axis_s + t·axis_t with s ∈ [0, width], t ∈ [0, height] [m]. For a
 *  vertical face the origin is the top-left corner seen from the front, axis_s points right and
 *  axis_t down, so the texture reads like an image of the face; normal() = axis_t × axis_s points
 *  to the front. Texel (col, row) covers s ∈ [col, col + 1)/ppm, t ∈ [row, row + 1)/ppm: an edge
 *  painted between two texels lies exactly at s = col/ppm, and bilinear sampling keeps it there.
 *
 *  The texture is kept as a mipmap pyramid against aliasing: texel i of level L is the mean of
 *  level-0 texels [2^L·i, 2^L·(i + 1)) per axis (borders replicated to even sizes), so texel
 *  centres of all levels stay aligned and an edge keeps its position at every level. */
class TexturedRectangle {
  public:
    /** \param axis_s, axis_t orthogonal unit vectors
     *  \param texture 8-bit grayscale, at least ceil(width·ppm) × ceil(height·ppm) texels */
    TexturedRectangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& axis_s,
                      const Eigen::Vector3d& axis_t, double width, double height,
                      const mrpt::img::CImage& texture, double pixels_per_metre);

    const Eigen::Vector3d& origin() const { return m_origin; }
    const Eigen::Vector3d& axisS() const { return m_axis_s; }
    const Eigen::Vector3d& axisT() const { return m_axis_t; }
    const Eigen::Vector3d& normal() const { return m_normal; }
    double width() const { return m_width; }
    double height() const { return m_height; }
    double pixelsPerMetre() const { return m_ppm; }
    /// Whether the face is vertical (a wall or a side of a piece of furniture).
    bool isVertical() const { return std::abs(m_normal.z()) < 1e-9; }

    /// The world point at face coordinates (s, t) [m].
    Eigen::Vector3d pointAt(double s, double t) const
    {
        return m_origin + s * m_axis_s + t * m_axis_t;
    }

    /// Parameter λ > 0 of the point p + λ·d where the ray crosses the rectangle, if it does.
    std::optional<double> intersect(const Eigen::Vector3d& p, const Eigen::Vector3d& d) const;

    /** Texture value [0-255] at (s, t) [m] for samples `footprint` level-0 texels apart:
     *  bilinear on the two mipmap levels around log2(footprint), linear between them. */
    float sample(double s, double t, double footprint) const;

  private:
    struct TLevel {
        int width = 0, height = 0;
        std::vector<uint8_t> texels;  ///< row-major
    };
    float sampleLevel(const TLevel& level, double x, double y) const;

    Eigen::Vector3d m_origin, m_axis_s, m_axis_t, m_normal;
    double m_width = 0, m_height = 0, m_ppm = 0;
    std::vector<TLevel> m_levels;  ///< mipmap pyramid, level 0 first
};

}  // namespace mrpt_vslam::sim
