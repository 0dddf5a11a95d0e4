#include <mrpt/core/bits_math.h>
#include <mrpt_vslam/sim/ConfigReading.h>
#include <mrpt_vslam/sim/StereoRenderer.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

namespace mrpt_vslam::sim {

namespace {

/// Sub-pixel rays closer than this [m] (camera z) are not rendered.
constexpr double kNearZ = 0.01;

/// The part of a convex polygon (camera frame) with z ≥ kNearZ (Sutherland–Hodgman, one plane).
std::vector<Eigen::Vector3d> clipToNearPlane(const std::vector<Eigen::Vector3d>& polygon)
{
    std::vector<Eigen::Vector3d> out;
    for (size_t i = 0; i < polygon.size(); i++) {
        const Eigen::Vector3d& a = polygon[i];
        const Eigen::Vector3d& b = polygon[(i + 1) % polygon.size()];
        const bool a_in = a.z() >= kNearZ, b_in = b.z() >= kNearZ;
        if (a_in) out.push_back(a);
        if (a_in != b_in) out.push_back(a + (kNearZ - a.z()) / (b.z() - a.z()) * (b - a));
    }
    return out;
}

}  // namespace

mrpt::img::TCamera StereoRenderer::camera() const
{
    mrpt::img::TCamera cam;
    cam.ncols = static_cast<uint32_t>(width);
    cam.nrows = static_cast<uint32_t>(height);
    cam.setIntrinsicParamsFromValues(fx, fy, cx, cy);
    cam.distortion = mrpt::img::DistortionModel::none;
    return cam;
}

mrpt::img::TStereoCamera StereoRenderer::stereoCamera() const
{
    mrpt::img::TStereoCamera stereo;
    stereo.leftCamera = camera();
    stereo.rightCamera = camera();
    stereo.rightCameraPose = mrpt::math::TPose3DQuat(baseline, 0, 0, 1, 0, 0, 0);
    return stereo;
}

Eigen::Vector2d StereoRenderer::fieldOfViewDeg() const
{
    // Edges of the image are the outer borders of the first and last pixels.
    const double h = std::atan((cx + 0.5) / fx) + std::atan((width - 0.5 - cx) / fx);
    const double v = std::atan((cy + 0.5) / fy) + std::atan((height - 0.5 - cy) / fy);
    return {mrpt::RAD2DEG(h), mrpt::RAD2DEG(v)};
}

TRenderedView StereoRenderer::renderView(const TexturedScene& scene,
                                         const mrpt::poses::CPose3D& camera_in_world) const
{
    const int ss = supersampling, sw = width * ss, sh = height * ss;
    const size_t n_sub = static_cast<size_t>(sw) * static_cast<size_t>(sh);
    constexpr float kFar = std::numeric_limits<float>::infinity();
    std::vector<float> z_buf(n_sub, kFar), s_buf(n_sub), t_buf(n_sub);
    std::vector<int> id_buf(n_sub, -1);

    const Eigen::Matrix3d Rt = camera_in_world.getRotationMatrix().asEigen().transpose();
    const Eigen::Vector3d C =
        Eigen::Vector3d(camera_in_world.x(), camera_in_world.y(), camera_in_world.z());
    // Sub-pixel (i, j) is at u = (i + ½)/ss − ½; its ray is r = (a_i, b_j, 1).
    std::vector<double> a(static_cast<size_t>(sw)), b(static_cast<size_t>(sh));
    for (int i = 0; i < sw; i++) a[static_cast<size_t>(i)] = ((i + 0.5) / ss - 0.5 - cx) / fx;
    for (int j = 0; j < sh; j++) b[static_cast<size_t>(j)] = ((j + 0.5) / ss - 0.5 - cy) / fy;

    // Per face: clip to the near plane, project, and test only the sub-pixels of each row that
    // lie within the projected polygon (±1 sub-pixel; the face coordinates decide).
    std::vector<Eigen::Vector3d> normals(scene.rectangles.size());
    for (size_t id = 0; id < scene.rectangles.size(); id++) {
        const TexturedRectangle& rect = scene.rectangles[id];
        const Eigen::Vector3d o = Rt * (rect.origin() - C);
        const Eigen::Vector3d es = Rt * rect.axisS(), et = Rt * rect.axisT();
        const Eigen::Vector3d n = et.cross(es);
        normals[id] = n;
        const std::vector<Eigen::Vector3d> visible =
            clipToNearPlane({o, o + rect.width() * es, o + rect.width() * es + rect.height() * et,
                             o + rect.height() * et});
        if (visible.size() < 3) continue;
        std::vector<Eigen::Vector2d> poly;  // in sub-pixel coordinates
        double j_min = 1e18, j_max = -1e18;
        for (const Eigen::Vector3d& p : visible) {
            const Eigen::Vector2d uv = project(p);
            poly.emplace_back((uv.x() + 0.5) * ss - 0.5, (uv.y() + 0.5) * ss - 0.5);
            j_min = std::min(j_min, poly.back().y()), j_max = std::max(j_max, poly.back().y());
        }
        const int j0 = std::max(0, static_cast<int>(std::floor(std::max(j_min, -1.0))));
        const int j1 = std::min(sh - 1, static_cast<int>(std::ceil(std::min(j_max, 1e9))));

        const double n_dot_o = n.dot(o);
        for (int j = j0; j <= j1; j++) {
            double x_min = 1e18, x_max = -1e18;
            for (size_t e = 0; e < poly.size(); e++) {
                const Eigen::Vector2d& p = poly[e];
                const Eigen::Vector2d& q = poly[(e + 1) % poly.size()];
                const double y_lo = std::min(p.y(), q.y()), y_hi = std::max(p.y(), q.y());
                if (j < y_lo - 1 || j > y_hi + 1) continue;
                const double y = std::clamp(static_cast<double>(j), y_lo, y_hi);
                const double x = y_hi - y_lo < 1e-9
                                     ? p.x()
                                     : p.x() + (y - p.y()) * (q.x() - p.x()) / (q.y() - p.y());
                const double x_other = y_hi - y_lo < 1e-9 ? q.x() : x;
                x_min = std::min({x_min, x, x_other}), x_max = std::max({x_max, x, x_other});
            }
            if (x_max < x_min) continue;
            const int i0 = std::max(0, static_cast<int>(std::floor(std::max(x_min, -2.0))) - 1);
            const int i1 = std::min(sw - 1, static_cast<int>(std::ceil(std::min(x_max, 1e9))) + 1);
            const double bj = b[static_cast<size_t>(j)];
            for (int i = i0; i <= i1; i++) {
                const double ai = a[static_cast<size_t>(i)];
                const double denom = n.x() * ai + n.y() * bj + n.z();
                if (std::abs(denom) < 1e-12) continue;
                const double z = n_dot_o / denom;  // ray–plane intersection, r_z = 1
                const size_t k = static_cast<size_t>(j) * sw + static_cast<size_t>(i);
                if (z <= kNearZ || z >= z_buf[k]) continue;
                const Eigen::Vector3d q = Eigen::Vector3d(z * ai, z * bj, z) - o;
                const double s = q.dot(es), t = q.dot(et);
                if (s < 0 || s > rect.width() || t < 0 || t > rect.height()) continue;
                z_buf[k] = static_cast<float>(z);
                id_buf[k] = static_cast<int>(id);
                s_buf[k] = static_cast<float>(s);
                t_buf[k] = static_cast<float>(t);
            }
        }
    }

    TRenderedView view;
    view.width = width;
    view.height = height;
    view.radiance.assign(static_cast<size_t>(width) * height, 0.0f);
    view.face.resize(view.radiance.size());
    const double f = std::sqrt(fx * fy);
    const float weight = 1.0f / static_cast<float>(ss * ss);
    for (int j = 0; j < sh; j++) {
        for (int i = 0; i < sw; i++) {
            const size_t k = static_cast<size_t>(j) * sw + static_cast<size_t>(i);
            const size_t pixel = static_cast<size_t>(j / ss) * width + static_cast<size_t>(i / ss);
            float value = static_cast<float>(background);
            if (id_buf[k] >= 0) {
                const size_t id = static_cast<size_t>(id_buf[k]);
                const TexturedRectangle& rect = scene.rectangles[id];
                const Eigen::Vector3d& n = normals[id];
                const double n_dot_r = std::abs(n.x() * a[static_cast<size_t>(i)] +
                                                n.y() * b[static_cast<size_t>(j)] + n.z());
                const double footprint = rect.pixelsPerMetre() * z_buf[k] /
                                         (f * ss * std::sqrt(std::max(n_dot_r, 0.01)));
                value = rect.sample(s_buf[k], t_buf[k], footprint);
            }
            view.radiance[pixel] += weight * value;
            if (j % ss == 0 && i % ss == 0) view.face[pixel] = id_buf[k];
        }
    }
    return view;
}

mrpt::img::CImage addPixelNoise(const TRenderedView& view, double noise_std,
                                mrpt::random::CRandomGenerator& rng)
{
    cv::Mat gray(view.height, view.width, CV_8UC1);
    for (int r = 0; r < view.height; r++) {
        uint8_t* row = gray.ptr<uint8_t>(r);
        for (int c = 0; c < view.width; c++) {
            const double v = view.radiance[static_cast<size_t>(r) * view.width + c] +
                             (noise_std > 0 ? noise_std * rng.drawGaussian1D_normalized() : 0);
            row[c] = cv::saturate_cast<uint8_t>(v);
        }
    }
    return mrpt::img::CImage(gray, mrpt::img::DEEP_COPY);
}

std::pair<mrpt::img::CImage, mrpt::img::CImage> StereoRenderer::render(
    const TexturedScene& scene, const mrpt::poses::CPose3D& left_in_world)
{
    mrpt::img::CImage left = addPixelNoise(renderView(scene, left_in_world), noise_std, m_rng);
    mrpt::img::CImage right =
        addPixelNoise(renderView(scene, left_in_world + rightCameraInLeft()), noise_std, m_rng);
    return {std::move(left), std::move(right)};
}

bool StereoRenderer::seesPoint(const TexturedScene& scene,
                               const mrpt::poses::CPose3D& left_in_world,
                               const Eigen::Vector3d& point, double margin_px) const
{
    for (const mrpt::poses::CPose3D& cam : {left_in_world, left_in_world + rightCameraInLeft()}) {
        const mrpt::math::TPoint3D p =
            cam.inverseComposePoint(mrpt::math::TPoint3D(point.x(), point.y(), point.z()));
        if (p.z <= kNearZ) return false;
        const Eigen::Vector2d uv = project({p.x, p.y, p.z});
        if (uv.x() < margin_px || uv.x() > width - 1 - margin_px || uv.y() < margin_px ||
            uv.y() > height - 1 - margin_px)
            return false;
        if (!scene.isVisibleFrom(point, Eigen::Vector3d(cam.x(), cam.y(), cam.z()))) return false;
    }
    return true;
}

void StereoRenderer::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                        const std::string& s)
{
    MRPT_LOAD_CONFIG_VAR(width, int, cfg, s);
    MRPT_LOAD_CONFIG_VAR(height, int, cfg, s);
    MRPT_LOAD_CONFIG_VAR(fx, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(fy, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(cx, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(cy, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(baseline, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(supersampling, int, cfg, s);
    MRPT_LOAD_CONFIG_VAR(noise_std, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(background, double, cfg, s);
    checkConfig(width >= 16 && width <= 4096, s, "width", "in [16, 4096]");
    checkConfig(height >= 16 && height <= 4096, s, "height", "in [16, 4096]");
    checkConfig(fx > 0, s, "fx", "> 0");
    checkConfig(fy > 0, s, "fy", "> 0");
    checkConfig(cx >= 0 && cx <= width - 1, s, "cx", "in [0, width - 1]");
    checkConfig(cy >= 0 && cy <= height - 1, s, "cy", "in [0, height - 1]");
    checkConfig(baseline > 0, s, "baseline", "> 0");
    checkConfig(supersampling >= 1 && supersampling <= 8, s, "supersampling", "in [1, 8]");
    checkConfig(noise_std >= 0, s, "noise_std", ">= 0");
    checkConfig(background >= 0 && background <= 255, s, "background", "in [0, 255]");
}

}  // namespace mrpt_vslam::sim
