#include <mrpt/img/CImage.h>
#include <mrpt_vslam/core/IntegralImage.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::core {

IntegralImage::IntegralImage(const mrpt::img::CImage& image)
{
    if (image.isEmpty() || image.getWidth() == 0 || image.getHeight() == 0) {
        throw std::invalid_argument("IntegralImage: empty image");
    }
    if (image.getPixelDepth() != mrpt::img::PixelDepth::D8U) {
        throw std::invalid_argument("IntegralImage: the image must have 8 bits per channel");
    }
    const mrpt::img::CImage gray(image, mrpt::img::FAST_REF_OR_CONVERT_TO_GRAY);
    m_width = gray.getWidth();
    m_height = gray.getHeight();
    const size_t stride = m_width + 1;
    m_table.assign(stride * (m_height + 1), 0);
    // I(x, y) = I(x, y − 1) + Σ_{c < x} p(c, y − 1): one running row sum per image row.
    for (size_t row = 0; row < m_height; row++) {
        const auto* pixels = gray.ptrLine<uint8_t>(static_cast<unsigned int>(row));
        const int64_t* above = &m_table[row * stride];
        int64_t* out = &m_table[(row + 1) * stride];
        int64_t row_sum = 0;
        for (size_t col = 0; col < m_width; col++) {
            row_sum += pixels[col];
            out[col + 1] = above[col + 1] + row_sum;
        }
    }
}

double IntegralImage::integralAt(double x, double y) const
{
    // Table index of the continuous coordinate x is x + ½ (pixel c spans [c − ½, c + ½)).
    const double tx = x + 0.5, ty = y + 0.5;
    const size_t i = std::min(static_cast<size_t>(std::max(0.0, std::floor(tx))), m_width - 1);
    const size_t j = std::min(static_cast<size_t>(std::max(0.0, std::floor(ty))), m_height - 1);
    const double fx = tx - static_cast<double>(i), fy = ty - static_cast<double>(j);
    const size_t stride = m_width + 1;
    const int64_t* t0 = &m_table[j * stride + i];
    const int64_t* t1 = t0 + stride;
    // F is bilinear inside the cell (the pixel value times the area of the partial rectangle).
    const double top = static_cast<double>(t0[0]) + fx * static_cast<double>(t0[1] - t0[0]);
    const double bottom = static_cast<double>(t1[0]) + fx * static_cast<double>(t1[1] - t1[0]);
    return top + fy * (bottom - top);
}

}  // namespace mrpt_vslam::core
