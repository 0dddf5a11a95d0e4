#include <mrpt/config/CConfigFileBase.h>
#include <mrpt_vslam/core/ConfigSectionWriter.h>
#include <mrpt_vslam/core/ImageFile.h>
#include <mrpt_vslam/core/ImageSize.h>
#include <mrpt_vslam/omni_fastslam/CeilingLightDetector.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace mrpt_vslam::omni_fastslam {

void CeilingLightDetector::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                        const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(intensity_threshold, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(min_blob_area, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(max_blob_area, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(pixel_std, double, cfg, section);
    lut.loadFromConfigFile(cfg, section);
    if (intensity_threshold < 0 || intensity_threshold > 254)
        throw std::invalid_argument("[" + section + "] intensity_threshold must be in [0, 254]");
    if (min_blob_area < 1 || max_blob_area < min_blob_area)
        throw std::invalid_argument("[" + section + "] need 1 <= min_blob_area <= max_blob_area");
    if (!(pixel_std > 0)) throw std::invalid_argument("[" + section + "] pixel_std must be > 0");
}

void CeilingLightDetector::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                                      const std::string& section) const
{
    const core::ConfigSectionWriter put(cfg, section);
    put("intensity_threshold", intensity_threshold, "[0-255] pixels above it belong to a light");
    put("min_blob_area", min_blob_area, "[px] smaller blobs are rejected as noise");
    put("max_blob_area", max_blob_area, "[px] larger blobs are rejected");
    put("pixel_std", pixel_std, "[px] std of a blob centroid");
    lut.saveToConfigFile(cfg, section);
}

CeilingLightDetector::CeilingLightDetector(const core::PajdlaBaksteinCamera& camera,
                                           const TOptions& options)
    : m_options(options), m_lut(camera, options.lut)
{
}

std::vector<CeilingLightDetector::TBlob> CeilingLightDetector::detectBlobs(
    const mrpt::img::CImage& image) const
{
    if (image.isEmpty()) throw std::invalid_argument("empty image");
    const mrpt::img::CImage gray_image(image, mrpt::img::FAST_REF_OR_CONVERT_TO_GRAY);
    cv::Mat gray;
    gray_image.asCvMat(gray, mrpt::img::SHALLOW_COPY);
    if (gray.type() != CV_8UC1) throw std::invalid_argument("expected an 8-bit image");

    cv::Mat mask, labels, stats, centroids;
    cv::threshold(gray, mask, m_options.intensity_threshold, 255, cv::THRESH_BINARY);
    const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);

    // Intensity-weighted centroids over each component's bounding box.
    std::vector<TBlob> blobs;
    for (int k = 1; k < n; k++) {
        const int area = stats.at<int>(k, cv::CC_STAT_AREA);
        if (area < m_options.min_blob_area || area > m_options.max_blob_area) continue;
        const int x0 = stats.at<int>(k, cv::CC_STAT_LEFT), y0 = stats.at<int>(k, cv::CC_STAT_TOP);
        const int w = stats.at<int>(k, cv::CC_STAT_WIDTH), h = stats.at<int>(k, cv::CC_STAT_HEIGHT);
        double sw = 0, su = 0, sv = 0;
        for (int y = y0; y < y0 + h; y++) {
            const auto* lab = labels.ptr<int>(y);
            const auto* pix = gray.ptr<uint8_t>(y);
            for (int x = x0; x < x0 + w; x++) {
                if (lab[x] != k) continue;
                const double wgt = pix[x];
                sw += wgt;
                su += wgt * x;
                sv += wgt * y;
            }
        }
        blobs.push_back({su / sw, sv / sw, area});
    }
    return blobs;
}

mrpt::obs::CObservationBearingRange::Ptr CeilingLightDetector::detect(
    const mrpt::obs::CObservationImage& obs, const std::string& sensor_label) const
{
    const auto& cam = m_lut.camera();
    core::requireIntactImageFile(obs.image);
    core::requireImageSize(obs.image, cam.width, cam.height);
    auto out = mrpt::obs::CObservationBearingRange::Create();
    out->timestamp = obs.timestamp;
    out->sensorLabel = sensor_label;
    out->sensorLocationOnRobot = obs.cameraPose;
    out->validCovariances = true;
    out->maxSensorDistance = 0;
    out->fieldOfView_yaw = 2 * M_PI;
    out->fieldOfView_pitch = cam.max_theta;

    const double var_px = m_options.pixel_std * m_options.pixel_std;
    for (const auto& blob : detectBlobs(obs.image)) {
        const auto z = m_lut.lookup(blob.u, blob.v);
        // a blob at or below the horizon (a camera wider than 180°) is not a ceiling light
        if (!z.valid || !(z.theta < M_PI / 2)) continue;
        // Q = J⁻¹ Σ_px J⁻ᵀ + diag(h²)/3 (step 4); J is singular at the image centre, where φ
        // carries no information: its variance is then capped at that of a uniform on [−π, π).
        const Eigen::Matrix2d J = cam.projectJacobian(z.phi, z.theta);
        Eigen::Matrix2d Q = Eigen::Matrix2d::Identity() * (M_PI * M_PI / 3);
        if (std::abs(J.determinant()) > 1e-9) {
            const Eigen::Matrix2d Jinv = J.inverse();
            Q = var_px * Jinv * Jinv.transpose();
        }
        Q(0, 0) = std::min(Q(0, 0) + z.phi_half_range * z.phi_half_range / 3, M_PI * M_PI / 3);
        Q(1, 1) += z.theta_half_range * z.theta_half_range / 3;

        mrpt::obs::CObservationBearingRange::TMeasurement m;
        m.range = std::numeric_limits<float>::quiet_NaN();
        m.yaw = static_cast<float>(z.phi);
        m.pitch = static_cast<float>(z.theta - M_PI / 2);  // pitch = −elevation = θ − π/2
        m.landmarkID = -1;
        m.covariance.setZero();
        m.covariance(1, 1) = Q(0, 0);
        m.covariance(1, 2) = m.covariance(2, 1) = Q(0, 1);
        m.covariance(2, 2) = Q(1, 1);
        out->sensedData.push_back(m);
    }
    return out;
}

}  // namespace mrpt_vslam::omni_fastslam
