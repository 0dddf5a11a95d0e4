#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace mrpt::img {
class CImage;
}

namespace mrpt_vslam::core {

/** Summed-area table of an 8-bit grayscale image (Viola & Jones 2001; Bay et al. 2008, Sec. 2):
 *  entry (x, y) holds the sum of all pixels with column < x and row < y, so the sum over any
 *  axis-aligned box costs four look-ups. Sums are exact (64-bit integers).
 *
 *  Sub-pixel boxes: seen as a function of continuous coordinates, with pixel (c, r) the unit
 *  square centred on (c, r), the integral F(x, y) of the piecewise-constant image over
 *  [−½, x) × [−½, y) is bilinear inside each cell of the table, so bilinear interpolation of the
 *  table gives it exactly (integralAt()). Box sums with real-valued corners follow from four
 *  such values.
 *
 *  Usage:
 *   1. Build once per image: `IntegralImage ii(gray);`.
 *   2. Query box sums: `ii.boxSum(col0, row0, col1, row1)`, or `integralAt(x, y)` for sub-pixel
 *      boxes.
 */
class IntegralImage {
  public:
    /** Builds the table of `image`; colour images are converted to grayscale first.
     *  \throw std::invalid_argument for an empty image or one that is not 8 bits per channel. */
    explicit IntegralImage(const mrpt::img::CImage& image);

    /** Sum of the pixels in columns [col0, col1) and rows [row0, row1) [gray levels].
     *  The box must lie inside the image (0 ≤ col0 ≤ col1 ≤ width, same for rows); unchecked. */
    int64_t boxSum(int col0, int row0, int col1, int row1) const
    {
        const size_t stride = m_width + 1;
        const size_t r0 = static_cast<size_t>(row0) * stride;
        const size_t r1 = static_cast<size_t>(row1) * stride;
        return m_table[r1 + col1] - m_table[r1 + col0] - m_table[r0 + col1] + m_table[r0 + col0];
    }

    /** Integral of the image over [−½, x) × [−½, y) in continuous pixel coordinates
     *  [gray levels · px²]; exact up to rounding. Requires −½ ≤ x ≤ width − ½ and
     *  −½ ≤ y ≤ height − ½ (unchecked). */
    double integralAt(double x, double y) const;

    /// Image width [px].
    int width() const { return static_cast<int>(m_width); }
    /// Image height [px].
    int height() const { return static_cast<int>(m_height); }

  private:
    size_t m_width = 0;
    size_t m_height = 0;
    std::vector<int64_t> m_table;  ///< (height + 1) × (width + 1), row-major; row 0 and col 0 are 0
};

}  // namespace mrpt_vslam::core
