#include <mrpt_vslam/sim/ConfigReading.h>
#include <mrpt_vslam/sim/LightBlobRenderer.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace mrpt_vslam::sim {

namespace {

/// Adds to `radiance` the covered fraction of each pixel of `box` for the shape `inside(u, v)`.
template <class Inside>
void addCoverage(cv::Mat& radiance, const cv::Rect& box, int ss, double weight, Inside inside)
{
    const double inv = 1.0 / ss;
    for (int row = box.y; row < box.y + box.height; row++) {
        for (int col = box.x; col < box.x + box.width; col++) {
            int hits = 0;
            for (int i = 0; i < ss; i++)
                for (int j = 0; j < ss; j++)
                    // Pixel (col, row) spans [col − ½, col + ½] × [row − ½, row + ½].
                    hits += inside(col - 0.5 + (j + 0.5) * inv, row - 0.5 + (i + 0.5) * inv);
            radiance.at<float>(row, col) += static_cast<float>(weight * hits * inv * inv);
        }
    }
}

/// Pixel box of the disk (centre c, unit normal n, radius) projected through Eq. 1, with margin.
cv::Rect diskBox(const TVisibleLight& light, double radius, const core::PajdlaBaksteinCamera& cam,
                 int margin)
{
    const Eigen::Vector3d& n = light.normal_in_camera;
    Eigen::Vector3d e1 = n.cross(Eigen::Vector3d::UnitX());
    if (e1.norm() < 1e-6) e1 = n.cross(Eigen::Vector3d::UnitY());
    e1.normalize();
    const Eigen::Vector3d e2 = n.cross(e1);
    double u_min = 1e9, u_max = -1e9, v_min = 1e9, v_max = -1e9;
    constexpr int kBoundaryPoints = 48;
    for (int k = 0; k < kBoundaryPoints; k++) {
        const double a = 2 * M_PI * k / kBoundaryPoints;
        const Eigen::Vector3d p =
            light.center_in_camera + radius * (std::cos(a) * e1 + std::sin(a) * e2);
        const Eigen::Vector2d ang =
            core::PajdlaBaksteinCamera::anglesOfPoint({p.x(), p.y(), p.z()});
        const Eigen::Vector2d uv = cam.project(ang.x(), ang.y());
        u_min = std::min(u_min, uv.x()), u_max = std::max(u_max, uv.x());
        v_min = std::min(v_min, uv.y()), v_max = std::max(v_max, uv.y());
    }
    const cv::Rect box(cv::Point(static_cast<int>(std::floor(u_min)) - margin,
                                 static_cast<int>(std::floor(v_min)) - margin),
                       cv::Point(static_cast<int>(std::ceil(u_max)) + margin + 1,
                                 static_cast<int>(std::ceil(v_max)) + margin + 1));
    return box & cv::Rect(0, 0, cam.width, cam.height);
}

}  // namespace

mrpt::img::CImage LightBlobRenderer::render(const TFrameDetections& frame, double light_radius,
                                            const PajdlaBaksteinInverse& model)
{
    const core::PajdlaBaksteinCamera& cam = model.camera();
    const cv::Rect image_rect(0, 0, cam.width, cam.height);
    cv::Mat radiance = cv::Mat::zeros(cam.height, cam.width, CV_32F);
    const int margin = 1;

    for (const TVisibleLight& light : frame.lights) {
        const Eigen::Vector3d& c = light.center_in_camera;
        const Eigen::Vector3d& n = light.normal_in_camera;
        const double nc = n.dot(c), r2 = light_radius * light_radius;
        addCoverage(radiance, diskBox(light, light_radius, cam, margin), supersampling, 1.0,
                    [&](double u, double v) {
                        // Ray–plane intersection: hit = t·d with n·(t·d − c) = 0.
                        const Eigen::Vector3d d = model.rayOfPixel({u, v});
                        const double nd = n.dot(d);
                        if (std::abs(nd) < 1e-12) return false;
                        const double t = nc / nd;
                        return t > 0 && (t * d - c).squaredNorm() <= r2;
                    });
    }
    for (const TSpuriousBlob& s : frame.spurious) {
        const int r = static_cast<int>(std::ceil(s.radius_px)) + margin;
        const cv::Rect box =
            cv::Rect(static_cast<int>(std::floor(s.uv.x())) - r,
                     static_cast<int>(std::floor(s.uv.y())) - r, 2 * r + 2, 2 * r + 2) &
            image_rect;
        const double r2 = s.radius_px * s.radius_px;
        addCoverage(radiance, box, supersampling, s.peak / (255.0 * gain), [&](double u, double v) {
            return (Eigen::Vector2d(u, v) - s.uv).squaredNorm() <= r2;
        });
    }
    if (blur_sigma_px > 0) cv::GaussianBlur(radiance, radiance, cv::Size(), blur_sigma_px);

    cv::Mat gray(cam.height, cam.width, CV_8U);
    for (int row = 0; row < cam.height; row++) {
        for (int col = 0; col < cam.width; col++) {
            double value = 255.0 * std::min(1.0, gain * radiance.at<float>(row, col));
            if (value >= 0.5) value += blob_noise_std * m_rng.drawGaussian1D_normalized();
            gray.at<uint8_t>(row, col) = cv::saturate_cast<uint8_t>(value);
        }
    }

    // Sparse sensor noise inside the image circle.
    const double r_circle = cam.radius(cam.max_theta);
    const auto sprinkle = [&](double fraction, int level_min, int level_max) {
        const int count = static_cast<int>(fraction * cam.width * cam.height);
        for (int i = 0; i < count; i++) {
            const int col =
                static_cast<int>(m_rng.drawUniform32bit() % static_cast<uint32_t>(cam.width));
            const int row =
                static_cast<int>(m_rng.drawUniform32bit() % static_cast<uint32_t>(cam.height));
            const int level =
                level_min + static_cast<int>(m_rng.drawUniform32bit() %
                                             static_cast<uint32_t>(level_max - level_min + 1));
            if (std::hypot(col - cam.u0, row / cam.beta - cam.v0) > r_circle) continue;
            uint8_t& px = gray.at<uint8_t>(row, col);
            px = std::max<uint8_t>(px, static_cast<uint8_t>(level));
        }
    };
    sprinkle(noise_pixel_fraction, 1, noise_max_level);
    sprinkle(hot_pixel_fraction, hot_pixel_min, 255);
    return mrpt::img::CImage(gray, mrpt::img::DEEP_COPY);
}

void LightBlobRenderer::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                           const std::string& s)
{
    MRPT_LOAD_CONFIG_VAR(supersampling, int, cfg, s);
    MRPT_LOAD_CONFIG_VAR(blur_sigma_px, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(gain, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(blob_noise_std, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(noise_pixel_fraction, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(noise_max_level, int, cfg, s);
    MRPT_LOAD_CONFIG_VAR(hot_pixel_fraction, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(hot_pixel_min, int, cfg, s);
    checkConfig(supersampling >= 1 && supersampling <= 16, s, "supersampling", "in [1, 16]");
    checkConfig(blur_sigma_px >= 0, s, "blur_sigma_px", ">= 0");
    checkConfig(gain >= 1, s, "gain", ">= 1");
    checkConfig(blob_noise_std >= 0, s, "blob_noise_std", ">= 0");
    checkConfig(noise_pixel_fraction >= 0 && noise_pixel_fraction <= 1, s, "noise_pixel_fraction",
                "in [0, 1]");
    checkConfig(noise_max_level >= 1 && noise_max_level <= 255, s, "noise_max_level",
                "in [1, 255]");
    checkConfig(hot_pixel_fraction >= 0 && hot_pixel_fraction <= 1, s, "hot_pixel_fraction",
                "in [0, 1]");
    checkConfig(hot_pixel_min >= 1 && hot_pixel_min <= 255, s, "hot_pixel_min", "in [1, 255]");
}

}  // namespace mrpt_vslam::sim
