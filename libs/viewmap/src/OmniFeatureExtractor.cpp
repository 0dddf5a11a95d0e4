#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/format.h>
#include <mrpt/img/CImage.h>
#include <mrpt_vslam/core/ImageFile.h>
#include <mrpt_vslam/core/ImageSize.h>
#include <mrpt_vslam/core/ParallelFor.h>
#include <mrpt_vslam/viewmap/OmniFeatureExtractor.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <tuple>

namespace mrpt_vslam::viewmap {
namespace {

// SURF descriptor layout (Bay et al. 2008, Sec. 4.1), as core::USurfDescriptor.
constexpr int kGrid = 20;              // samples per side of the 20s window
constexpr int kSamplesPerSub = 5;      // samples per side of a sub-region
constexpr double kSigmaInScale = 3.3;  // Gaussian σ of the weights [s]
/** Squared norm of the raw descriptor below which the patch is flat: the sub-pixel integrals of
 *  a constant patch cancel only up to rounding (~1e-14 here), real texture gives ≥ 1. */
constexpr double kMinNorm2 = 1e-6;
/// Half side of the descriptor window [s]: 10 s of samples plus the Haar boxes' half side.
constexpr double kWindowHalfSide = 10.5;

/// exp(−u² / (2·3.3²)) of the sample offsets u = (i + ½) − 10 [s].
const std::array<double, kGrid>& sampleWeights()
{
    static const std::array<double, kGrid> weights = [] {
        std::array<double, kGrid> w;
        for (int i = 0; i < kGrid; i++) {
            const double u = i + 0.5 - 0.5 * kGrid;
            w[size_t(i)] = std::exp(-u * u / (2 * kSigmaInScale * kSigmaInScale));
        }
        return w;
    }();
    return weights;
}

}  // namespace

core::FastHessianDetector::TOptions OmniFeatureExtractor::TOptions::defaultDetector()
{
    core::FastHessianDetector::TOptions d;
    d.hessian_threshold = 10.0;
    d.octaves = 3;
    d.initial_step = 2;
    return d;
}

void OmniFeatureExtractor::TOptions::validate() const
{
    detector.validate();
    if (max_features < 1) {
        throw std::invalid_argument(
            mrpt::format("OmniFeatureExtractor: max_features = %d must be >= 1", max_features));
    }
    if (!(window_margin >= 0 && window_margin <= 1)) {
        throw std::invalid_argument(mrpt::format(
            "OmniFeatureExtractor: window_margin = %g must be in [0, 1]", window_margin));
    }
}

void OmniFeatureExtractor::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                        const std::string& section)
{
    detector.loadFromConfigFile(cfg, section);
    MRPT_LOAD_CONFIG_VAR(max_features, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(window_margin, double, cfg, section);
    validate();
}

void OmniFeatureExtractor::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                                      const std::string& s) const
{
    detector.saveToConfigFile(c, s);
    MRPT_SAVE_CONFIG_VAR_COMMENT(max_features, "the strongest feature points kept per image");
    MRPT_SAVE_CONFIG_VAR_COMMENT(window_margin,
                                 "[-] part of the descriptor half window kept in the image circle");
}

OmniFeatureExtractor::OmniFeatureExtractor(const core::UnifiedSphereCamera& camera,
                                           const Eigen::Matrix3d& camera_to_robot,
                                           const TOptions& options)
    : m_options(options), m_detector(options.detector)
{
    setCamera(camera);
    m_options.validate();
    setCameraToRobot(camera_to_robot);
}

void OmniFeatureExtractor::setCamera(const core::UnifiedSphereCamera& camera)
{
    camera.validate();
    m_camera = camera;
}

void OmniFeatureExtractor::setCameraToRobot(const Eigen::Matrix3d& camera_to_robot)
{
    const double off = (camera_to_robot.transpose() * camera_to_robot - Eigen::Matrix3d::Identity())
                           .cwiseAbs()
                           .maxCoeff();
    if (!(off < 1e-9) || !(camera_to_robot.determinant() > 0)) {
        throw std::invalid_argument(
            "OmniFeatureExtractor: camera_to_robot must be a rotation matrix");
    }
    m_camera_to_robot = camera_to_robot;
}

std::optional<core::USurfDescriptor::TDescriptor> OmniFeatureExtractor::orientedDescriptor(
    const core::IntegralImage& integral, double x, double y, double s, const Eigen::Vector2d& down)
{
    return orientedDescriptor(TIntegralTable(integral), x, y, s, down);
}

std::optional<core::USurfDescriptor::TDescriptor> OmniFeatureExtractor::orientedDescriptor(
    const TIntegralTable& table, double x, double y, double s, const Eigen::Vector2d& down)
{
    // Samples reach 9.5√2 s from the keypoint, their Haar boxes s further along each axis.
    const double reach = (9.5 * M_SQRT2 + 1) * s;
    if (!(x - reach >= -0.5 && y - reach >= -0.5 && x + reach <= table.width - 0.5 &&
          y + reach <= table.height - 0.5)) {
        return std::nullopt;
    }
    const auto& weight = sampleWeights();
    const double vx = down.x(), vy = down.y(), ux = vy, uy = -vx;
    const double inv_half_area = 1 / (2 * s * s);
    std::array<double, core::USurfDescriptor::kSize> v{};
    for (int r = 0; r < kGrid; r++) {
        const double b = (r + 0.5 - 0.5 * kGrid) * s;
        for (int c = 0; c < kGrid; c++) {
            const double a = (c + 0.5 - 0.5 * kGrid) * s;
            const double px = x + a * ux + b * vx, py = y + a * uy + b * vy;
            // Integrals at (px + (j − 1)s, py + (i − 1)s); the centre is not needed.
            const double f00 = table.at(px - s, py - s), f01 = table.at(px, py - s),
                         f02 = table.at(px + s, py - s), f10 = table.at(px - s, py),
                         f12 = table.at(px + s, py), f20 = table.at(px - s, py + s),
                         f21 = table.at(px, py + s), f22 = table.at(px + s, py + s);
            // Right minus left half, bottom minus top half of the 2s box (mean gray levels).
            const double dx = (f22 - 2 * f21 - f02 + 2 * f01 + f20 - f00) * inv_half_area;
            const double dy = (f22 - f20 - 2 * f12 + 2 * f10 + f02 - f00) * inv_half_area;
            const double w = weight[size_t(r)] * weight[size_t(c)];
            const double du = w * (dx * ux + dy * uy), dv = w * (dx * vx + dy * vy);
            double* sub = &v[size_t(4 * (4 * (r / kSamplesPerSub) + c / kSamplesPerSub))];
            sub[0] += du;
            sub[1] += dv;
            sub[2] += std::abs(du);
            sub[3] += std::abs(dv);
        }
    }
    double norm2 = 0;
    for (double e : v) norm2 += e * e;
    if (!(norm2 > kMinNorm2)) return std::nullopt;  // flat patch (up to rounding)
    const double inv_norm = 1 / std::sqrt(norm2);
    core::USurfDescriptor::TDescriptor out;
    for (size_t k = 0; k < out.size(); k++) out[k] = float(v[k] * inv_norm);
    return out;
}

OmniFeatureExtractor::TIntegralTable::TIntegralTable(const core::IntegralImage& integral)
    : width(integral.width()), height(integral.height()), stride(size_t(width) + 1)
{
    values.resize(stride * (size_t(height) + 1));
    for (int row = 0; row <= height; row++) {
        for (int col = 0; col <= width; col++) {
            values[size_t(row) * stride + size_t(col)] = double(integral.boxSum(0, 0, col, row));
        }
    }
}

std::optional<OmniFeatureExtractor::TDescribed> OmniFeatureExtractor::describe(
    const core::FastHessianDetector::TKeypoint& kp, const TIntegralTable& table) const
{
    const auto ray = m_camera.unproject(Eigen::Vector2d(kp.x, kp.y));
    if (!ray) return std::nullopt;
    // Image direction of the robot's −z at the point: the descriptor's "down" axis.
    const Eigen::Vector3d zenith_in_camera = m_camera_to_robot.transpose().col(2);
    const Eigen::Vector3d to_zenith = zenith_in_camera - zenith_in_camera.dot(*ray) * *ray;
    const Eigen::Vector2d up = m_camera.projectJacobian(*ray) * to_zenith;
    if (!(up.norm() > 1e-9)) return std::nullopt;  // the zenith itself: no orientation
    const Eigen::Vector2d down = -up.normalized();
    // The window's corners (shrunk by window_margin) inside the image circle.
    const double half = m_options.window_margin * kWindowHalfSide * kp.scale;
    const Eigen::Vector2d u_axis(down.y(), -down.x());
    for (const double a : {-half, half})
        for (const double b : {-half, half})
            if (!m_camera.unproject(Eigen::Vector2d(kp.x, kp.y) + a * u_axis + b * down))
                return std::nullopt;
    const auto descriptor = orientedDescriptor(table, kp.x, kp.y, kp.scale, down);
    if (!descriptor) return std::nullopt;
    return TDescribed{*ray, *descriptor};
}

TViewFeatures OmniFeatureExtractor::extract(const mrpt::img::CImage& image) const
{
    core::requireIntactImageFile(image);
    core::requireImageSize(image, m_camera.width, m_camera.height);
    const core::IntegralImage integral(image);  // grayscale, 8-bit check
    std::vector<core::FastHessianDetector::TKeypoint> keypoints =
        m_detector.detect(integral, m_threads);
    const TIntegralTable table(integral);
    std::sort(keypoints.begin(), keypoints.end(), [](const auto& a, const auto& b) {
        return std::make_tuple(-a.response, a.y, a.x, a.scale) <
               std::make_tuple(-b.response, b.y, b.x, b.scale);
    });

    const size_t capacity = std::min(keypoints.size(), size_t(m_options.max_features));
    TViewFeatures f;
    f.pixels.resize(2, Eigen::Index(capacity));
    f.rays.resize(3, Eigen::Index(capacity));
    f.scales.reserve(capacity);
    f.laplacian_signs.reserve(capacity);
    f.descriptors.reserve(capacity);
    // the strongest keypoints that have a feature, described a batch at a time in parallel
    std::vector<std::optional<TDescribed>> batch;
    for (size_t next = 0; next < keypoints.size() && f.size() < capacity;) {
        batch.assign(std::min(keypoints.size() - next, capacity - f.size()), std::nullopt);
        core::parallelFor(batch.size(), m_threads,
                          [&](size_t i) { batch[i] = describe(keypoints[next + i], table); });
        for (size_t i = 0; i < batch.size(); i++) {
            if (!batch[i]) continue;
            const auto& kp = keypoints[next + i];
            const auto k = Eigen::Index(f.size());
            f.pixels.col(k) << float(kp.x), float(kp.y);
            f.rays.col(k) = m_camera_to_robot * batch[i]->ray;
            f.scales.push_back(float(kp.scale));
            f.laplacian_signs.push_back(int8_t(kp.laplacian_sign));
            f.descriptors.push_back(batch[i]->descriptor);
        }
        next += batch.size();
    }
    f.pixels.conservativeResize(2, Eigen::Index(f.size()));
    f.rays.conservativeResize(3, Eigen::Index(f.size()));
    return f;
}

}  // namespace mrpt_vslam::viewmap
