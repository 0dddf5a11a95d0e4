#include <mrpt_vslam/sim/TexturedRectangle.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>

namespace mrpt_vslam::sim {

TexturedRectangle::TexturedRectangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& axis_s,
                                     const Eigen::Vector3d& axis_t, double width, double height,
                                     const mrpt::img::CImage& texture, double pixels_per_metre)
    : m_origin(origin),
      m_axis_s(axis_s),
      m_axis_t(axis_t),
      m_normal(axis_t.cross(axis_s)),
      m_width(width),
      m_height(height),
      m_ppm(pixels_per_metre)
{
    const cv::Mat& mat = texture.asCvMatRef();
    if (mat.type() != CV_8UC1 || mat.cols < std::ceil(width * m_ppm - 1e-9) ||
        mat.rows < std::ceil(height * m_ppm - 1e-9))
        throw std::invalid_argument(
            "TexturedRectangle: texture must be 8-bit gray and cover the face");
    TLevel level0;
    level0.width = mat.cols;
    level0.height = mat.rows;
    level0.texels.resize(static_cast<size_t>(mat.cols) * static_cast<size_t>(mat.rows));
    for (int r = 0; r < mat.rows; r++)
        std::copy_n(mat.ptr<uint8_t>(r), mat.cols, level0.texels.begin() + r * mat.cols);
    m_levels.push_back(std::move(level0));

    while (m_levels.back().width > 1 || m_levels.back().height > 1) {
        const TLevel& fine = m_levels.back();
        TLevel coarse;
        coarse.width = (fine.width + 1) / 2;
        coarse.height = (fine.height + 1) / 2;
        coarse.texels.resize(static_cast<size_t>(coarse.width) * coarse.height);
        const auto at = [&](int x, int y) {
            return static_cast<int>(
                fine.texels[static_cast<size_t>(std::min(y, fine.height - 1)) * fine.width +
                            std::min(x, fine.width - 1)]);
        };
        for (int y = 0; y < coarse.height; y++)
            for (int x = 0; x < coarse.width; x++)
                coarse.texels[static_cast<size_t>(y) * coarse.width + x] =
                    static_cast<uint8_t>((at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) +
                                          at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1) + 2) /
                                         4);
        m_levels.push_back(std::move(coarse));
    }
}

std::optional<double> TexturedRectangle::intersect(const Eigen::Vector3d& p,
                                                   const Eigen::Vector3d& d) const
{
    const double nd = m_normal.dot(d);
    if (std::abs(nd) < 1e-12) return std::nullopt;
    const double lambda = m_normal.dot(m_origin - p) / nd;
    if (lambda <= 0) return std::nullopt;
    const Eigen::Vector3d q = p + lambda * d - m_origin;
    const double s = q.dot(m_axis_s), t = q.dot(m_axis_t);
    if (s < 0 || s > m_width || t < 0 || t > m_height) return std::nullopt;
    return lambda;
}

float TexturedRectangle::sampleLevel(const TLevel& level, double x, double y) const
{
    // (x, y) in texels of this level, texel centres at integers.
    x = std::clamp(x, 0.0, level.width - 1.0);
    y = std::clamp(y, 0.0, level.height - 1.0);
    const int x0 = std::min(static_cast<int>(x), level.width - 1);
    const int y0 = std::min(static_cast<int>(y), level.height - 1);
    const int x1 = std::min(x0 + 1, level.width - 1), y1 = std::min(y0 + 1, level.height - 1);
    const double fx = x - x0, fy = y - y0;
    const uint8_t* row0 = &level.texels[static_cast<size_t>(y0) * level.width];
    const uint8_t* row1 = &level.texels[static_cast<size_t>(y1) * level.width];
    const double top = row0[x0] + fx * (row0[x1] - row0[x0]);
    const double bottom = row1[x0] + fx * (row1[x1] - row1[x0]);
    return static_cast<float>(top + fy * (bottom - top));
}

float TexturedRectangle::sample(double s, double t, double footprint) const
{
    const double lod = footprint > 1 ? std::log2(footprint) : 0.0;
    const size_t max_level = m_levels.size() - 1;
    const size_t l0 = std::min(static_cast<size_t>(lod), max_level);
    const auto at_level = [&](size_t l) {
        const double scale = m_ppm / static_cast<double>(1u << l);
        return sampleLevel(m_levels[l], s * scale - 0.5, t * scale - 0.5);
    };
    const float v0 = at_level(l0);
    if (l0 == max_level) return v0;
    const float f = static_cast<float>(lod - static_cast<double>(l0));
    return f > 0 ? v0 + f * (at_level(l0 + 1) - v0) : v0;
}

}  // namespace mrpt_vslam::sim
