#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/format.h>
#include <mrpt/img/CImage.h>
#include <mrpt_vslam/core/ConfigSectionWriter.h>
#include <mrpt_vslam/core/EndsWith.h>
#include <mrpt_vslam/core/ImageFile.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/multirobot/StereoFrontEnd.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>

namespace mrpt_vslam::multirobot {

void StereoFrontEnd::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                  const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(max_corners, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(harris_quality, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(min_corner_distance, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(harris_block_size, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(harris_k, double, cfg, section);
    matching.loadFromConfigFile(cfg, section);
    MRPT_LOAD_CONFIG_VAR(min_depth, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(max_depth, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(usurf_scale, double, cfg, section);
    pixel_noise.sigma_disparity =
        cfg.read_double(section, "sigma_disparity", pixel_noise.sigma_disparity);
    pixel_noise.sigma_row = cfg.read_double(section, "sigma_row", pixel_noise.sigma_row);
    pixel_noise.sigma_col = cfg.read_double(section, "sigma_col", pixel_noise.sigma_col);
    MRPT_LOAD_CONFIG_VAR(track_search_radius, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(track_ratio, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(track_max_descriptor_distance, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(min_track_length, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(max_landmarks_per_frame, int, cfg, section);
    validate(section);
}

void StereoFrontEnd::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                                const std::string& section) const
{
    const core::ConfigSectionWriter put(cfg, section);
    put("max_corners", max_corners, "Harris corners kept per left image, strongest first");
    put("harris_quality", harris_quality, "minimum Harris response / strongest response");
    put("min_corner_distance", min_corner_distance, "[px] minimum distance between corners");
    put("harris_block_size", harris_block_size, "[px] structure-tensor window side");
    put("harris_k", harris_k, "Harris & Stephens k");
    matching.saveToConfigFile(cfg, section);
    put("min_depth", min_depth, "[m] nearer stereo points are dropped");
    put("max_depth", max_depth, "[m] farther stereo points are dropped");
    put("usurf_scale", usurf_scale, "[px] U-SURF scale s (window 20 s)");
    put("sigma_disparity", pixel_noise.sigma_disparity, "[px] sigma_d of R_t (Gil et al. 2010: 1)");
    put("sigma_row", pixel_noise.sigma_row, "[px] sigma_r of R_t (Gil et al. 2010: 10)");
    put("sigma_col", pixel_noise.sigma_col, "[px] sigma_c of R_t (Gil et al. 2010: 10)");
    put("track_search_radius", track_search_radius, "[px] image motion between frames");
    put("track_ratio", track_ratio, "descriptor ratio test of the tracking");
    put("track_max_descriptor_distance", track_max_descriptor_distance,
        "largest U-SURF distance of a tracked point");
    put("min_track_length", min_track_length, "frames a point must be tracked (paper: 3)");
    put("max_landmarks_per_frame", max_landmarks_per_frame,
        "most landmarks per frame; 0 = no limit");
}

void StereoFrontEnd::TOptions::validate(const std::string& section) const
{
    using core::requireKey;
    const auto positive = [&](double v, std::string_view key) {
        requireKey(v > 0 && std::isfinite(v), section, key, "must be > 0");
    };
    requireKey(max_corners >= 1, section, "max_corners", "must be >= 1");
    requireKey(harris_quality > 0 && harris_quality < 1, section, "harris_quality",
               "must be in (0, 1)");
    requireKey(min_corner_distance >= 0 && std::isfinite(min_corner_distance), section,
               "min_corner_distance", "must be >= 0");
    requireKey(harris_block_size >= 2, section, "harris_block_size", "must be >= 2");
    requireKey(harris_k > 0 && harris_k < 0.25, section, "harris_k", "must be in (0, 0.25)");
    matching.validate(section);
    requireKey(min_depth > 0, section, "min_depth", "must be > 0");
    requireKey(max_depth > min_depth && std::isfinite(max_depth), section, "max_depth",
               "must be finite and > min_depth");
    positive(usurf_scale, "usurf_scale");
    positive(pixel_noise.sigma_disparity, "sigma_disparity");
    positive(pixel_noise.sigma_row, "sigma_row");
    positive(pixel_noise.sigma_col, "sigma_col");
    positive(track_search_radius, "track_search_radius");
    requireKey(track_ratio > 0 && track_ratio <= 1, section, "track_ratio", "must be in (0, 1]");
    requireKey(track_max_descriptor_distance > 0 && track_max_descriptor_distance <= 2, section,
               "track_max_descriptor_distance", "must be in (0, 2]");
    requireKey(min_track_length >= 1, section, "min_track_length", "must be >= 1");
    requireKey(max_landmarks_per_frame >= 0, section, "max_landmarks_per_frame",
               "must be >= 0 (0 = no limit)");
}

StereoFrontEnd::StereoFrontEnd(const TOptions& options) : m_options(options)
{
    m_options.validate("StereoFrontEnd");
}

std::string StereoFrontEnd::landmarksLabel(const std::string& stereo_label)
{
    const std::string suffix = "_STEREO";
    if (core::endsWith(stereo_label, suffix))
        return stereo_label.substr(0, stereo_label.size() - suffix.size()) + "_LANDMARKS";
    return stereo_label + "_LANDMARKS";
}

void StereoFrontEnd::reset() { m_points.clear(); }

StereoFrontEnd::TFrameStats& StereoFrontEnd::TFrameStats::operator+=(const TFrameStats& frame)
{
    frames += frame.frames;
    rectified += frame.rectified;
    corners += frame.corners;
    matched += frame.matched;
    nearest_match = std::min(nearest_match, frame.nearest_match);
    farthest_match = std::max(farthest_match, frame.farthest_match);
    stereo += frame.stereo;
    points += frame.points;
    tracked += frame.tracked;
    eligible += frame.eligible;
    emitted += frame.emitted;
    if (rectified_because.empty()) rectified_because = frame.rectified_because;
    return *this;
}

std::string StereoFrontEnd::whyNoLandmarks(const TFrameStats& frames, const TOptions& o)
{
    const auto n = [](size_t count) { return std::to_string(count); };
    if (frames.emitted > 0) return {};
    if (frames.corners == 0)
        return "no Harris corner in the left images (step 1: blank or textureless images, or "
               "too small for the correlation patch and the descriptor window; "
               "harris_quality, ncc_window, usurf_scale)";
    if (frames.matched == 0)
        return "none of the " + n(frames.corners) +
               " corners matched along its row of the right image (step 2: check the "
               "calibration; min_ncc, uniqueness_ratio, min_disparity, max_disparity)";
    if (frames.stereo == 0)
        return mrpt::format(
            "none of the %zu matched corners lies within min_depth, max_depth = %g, %g m: "
            "they lie at %.2f-%.2f m (step 2: check the depth range and the calibration's "
            "baseline)",
            frames.matched, o.min_depth, o.max_depth, frames.nearest_match, frames.farthest_match);
    if (frames.points == 0)
        return "none of the " + n(frames.stereo) +
               " stereo points got a U-SURF descriptor (step 3: flat patches; usurf_scale)";
    // every eligible point is emitted (step 6 caps at >= 1)
    return "none of the " + n(frames.points) + " stereo points was tracked over " +
           n(static_cast<size_t>(o.min_track_length)) +
           " consecutive pairs (step 5: too few pairs, or the image moves farther than "
           "track_search_radius between them; track_ratio, track_max_descriptor_distance, "
           "min_track_length)";
}

std::vector<StereoFrontEnd::TPoint> StereoFrontEnd::detect(
    const mrpt::obs::CObservationStereoImages& obs, const StereoGeometry& geometry)
{
    using mrpt::img::CImage;
    const CImage left(obs.imageLeft, mrpt::img::FAST_REF_OR_CONVERT_TO_GRAY);
    const CImage right(obs.imageRight, mrpt::img::FAST_REF_OR_CONVERT_TO_GRAY);
    const StereoMatcher matcher(left, right, m_options.matching);  // checks the images
    const cv::Mat gray = left.asCvMat<cv::Mat>(mrpt::img::SHALLOW_COPY);
    const core::USurfDescriptor usurf(left);
    m_stats = {};
    m_stats.frames = 1;

    // Step 1: Harris corners where the correlation patch and the U-SURF window both fit
    // (the descriptor needs x − 10.5 s ≥ −½, USurfDescriptor::fitsInImage)
    const double s = m_options.usurf_scale;
    const int margin = std::max(matcher.halfWindow(), static_cast<int>(std::ceil(10.5 * s - 0.5)));
    std::vector<TPoint> points;
    if (gray.cols <= 2 * margin || gray.rows <= 2 * margin) return points;
    cv::Mat mask = cv::Mat::zeros(gray.size(), CV_8UC1);
    mask(cv::Rect(margin, margin, gray.cols - 2 * margin, gray.rows - 2 * margin)).setTo(255);
    const int column_offset = static_cast<int>(std::lround(geometry.disparityOffset()));
    std::vector<cv::Point2f> corners;
    cv::goodFeaturesToTrack(gray, corners, m_options.max_corners, m_options.harris_quality,
                            m_options.min_corner_distance, mask, m_options.harris_block_size, true,
                            m_options.harris_k);
    m_stats.corners = corners.size();

    for (const cv::Point2f& corner : corners) {
        const int col = static_cast<int>(std::lround(corner.x));
        const int row = static_cast<int>(std::lround(corner.y));
        // Step 2: stereo correspondence, depth range
        const auto stereo = matcher.match(row, col, column_offset);
        if (!stereo) continue;
        const TStereoPixel px{static_cast<double>(row), static_cast<double>(col),
                              stereo->disparity - geometry.disparityOffset()};
        if (!(px.disparity > 0)) continue;  // at or beyond infinity
        const mrpt::math::TPoint3D z = geometry.triangulate(px);
        m_stats.matched++;
        m_stats.nearest_match = std::min(m_stats.nearest_match, z.z);
        m_stats.farthest_match = std::max(m_stats.farthest_match, z.z);
        if (z.z < m_options.min_depth || z.z > m_options.max_depth) continue;
        m_stats.stereo++;
        // Step 3: U-SURF descriptor at the fixed scale
        const auto descriptor = usurf.compute(col, row, s);
        if (!descriptor) continue;
        // Step 4: z_t and R_t
        TPoint p;
        p.pixel = px;
        p.point = z;
        p.cov = geometry.covariance(px, m_options.pixel_noise);
        p.descriptor = *descriptor;
        p.ncc = stereo->ncc;
        points.push_back(p);
    }
    m_stats.points = points.size();
    return points;
}

mrpt::obs::CObservationVisualLandmarks::Ptr StereoFrontEnd::process(
    const mrpt::obs::CObservationStereoImages& obs)
{
    if (!obs.hasImageRight)
        throw std::invalid_argument(
            "the stereo observation has no right image (hasImageRight "
            "is false)");
    core::requireIntactImageFile(obs.imageLeft, "the left image");
    core::requireIntactImageFile(obs.imageRight, "the right image");
    if (obs.imageLeft.isEmpty()) throw std::invalid_argument("left image is empty");
    if (obs.imageRight.isEmpty()) throw std::invalid_argument("right image is empty");
    for (const auto* image : {&obs.imageLeft, &obs.imageRight})
        if (image->getWidth() != obs.leftCamera.ncols || image->getHeight() != obs.leftCamera.nrows)
            throw std::invalid_argument(
                "images are " + std::to_string(image->getWidth()) + "x" +
                std::to_string(image->getHeight()) + " but the calibration is for " +
                std::to_string(obs.leftCamera.ncols) + "x" + std::to_string(obs.leftCamera.nrows));
    // a head whose calibration is not rectified is rectified here, its camera pose with it
    std::string why = StereoGeometry::whyNotRectified(obs);
    std::optional<mrpt::obs::CObservationStereoImages> rectified;
    if (!why.empty()) rectified = m_rectifier.rectify(obs);
    const auto& pair = rectified ? *rectified : obs;
    const StereoGeometry geometry = StereoGeometry::fromObservation(pair);
    const mrpt::poses::CPose3D camera_on_robot(pair.cameraPose);
    for (int i = 0; i < 6; i++)
        if (!std::isfinite(camera_on_robot[i]))
            throw std::invalid_argument("the camera pose on the robot is not finite");

    // Everything that can fail is done before the tracks change.
    std::vector<TPoint> current = detect(pair, geometry);
    m_stats.rectified = why.empty() ? 0 : 1;
    m_stats.rectified_because = std::move(why);
    track(current);
    m_points = std::move(current);
    const std::vector<size_t> emitted = selectEmitted();

    auto out = mrpt::obs::CObservationVisualLandmarks::Create();
    out->timestamp = obs.timestamp;
    out->sensorLabel = landmarksLabel(obs.sensorLabel);
    out->refCameraPose = camera_on_robot;
    for (const size_t i : emitted) {
        const TPoint& p = m_points[i];
        mrpt::maps::CLandmark lm;
        lm.pose_mean = p.point;
        lm.pose_cov_11 = static_cast<float>(p.cov(0, 0));
        lm.pose_cov_22 = static_cast<float>(p.cov(1, 1));
        lm.pose_cov_33 = static_cast<float>(p.cov(2, 2));
        lm.pose_cov_12 = static_cast<float>(p.cov(0, 1));
        lm.pose_cov_13 = static_cast<float>(p.cov(0, 2));
        lm.pose_cov_23 = static_cast<float>(p.cov(1, 2));
        lm.ID = p.track_id;
        lm.seenTimesCount = p.track_length;
        lm.timestampLastSeen = obs.timestamp;
        mrpt::vision::CFeature f{};  // value-initialized: CFeature leaves x2, y2 unset
        f.type = mrpt::vision::featHarris;
        f.keypoint.pt.x = static_cast<float>(p.pixel.col);
        f.keypoint.pt.y = static_cast<float>(p.pixel.row);
        f.keypoint.ID = static_cast<mrpt::vision::TFeatureID>(p.track_id);
        f.descriptors.SURF = std::vector<float>(p.descriptor.begin(), p.descriptor.end());
        lm.features.push_back(std::move(f));
        out->landmarks.landmarks.push_back(lm);
    }
    m_stats.emitted = emitted.size();
    return out;
}

}  // namespace mrpt_vslam::multirobot
