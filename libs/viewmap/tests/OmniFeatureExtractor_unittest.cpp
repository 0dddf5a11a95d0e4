// Feature points of omni images drawn here (no rendering): blob directions, determinism, the
// max_features prefix, colour input, the mounting rotation, invariance of the oriented
// descriptor to a turn of the robot, and the options.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/img/CImage.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/IntegralImage.h>
#include <mrpt_vslam/core/USurfDescriptor.h>
#include <mrpt_vslam/viewmap/OmniFeatureExtractor.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

using mrpt::DEG2RAD;
using mrpt::img::CImage;
using mrpt_vslam::core::UnifiedSphereCamera;
using mrpt_vslam::core::USurfDescriptor;
using mrpt_vslam::viewmap::OmniFeatureExtractor;
using mrpt_vslam::viewmap::TViewFeatures;

namespace {

/// The camera of the omni-views scenario (unified sphere, ξ 0.9, 640 × 480, up to 100°).
UnifiedSphereCamera omniCamera()
{
    UnifiedSphereCamera c;
    c.xi = 0.9;
    c.fx = c.fy = 172;
    c.cx = 319.5;
    c.cy = 239.5;
    c.max_theta = DEG2RAD(100.0);
    return c;
}

/// A square camera centred on a pixel, so that turning the image by 90° about the centre is a
/// permutation of its pixels.
UnifiedSphereCamera squareCamera()
{
    UnifiedSphereCamera c = omniCamera();
    c.width = c.height = 401;
    c.cx = c.cy = 200;
    c.fx = c.fy = 140;
    return c;
}

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// Dark Gaussian blobs (σ = 3 px, depth 90 gray levels) on a gray background at the pixels of
/// `rays`; the outside of the image circle is black, as in rendered images.
CImage blobImage(const UnifiedSphereCamera& camera, const std::vector<Eigen::Vector3d>& rays)
{
    std::vector<Eigen::Vector2d> centres;
    for (const auto& r : rays) centres.push_back(*camera.project(r));
    CImage img(camera.width, camera.height, mrpt::img::CH_GRAY);
    for (int row = 0; row < camera.height; row++) {
        for (int col = 0; col < camera.width; col++) {
            double v = 0;
            if (camera.unproject(Eigen::Vector2d(col, row))) {
                v = 170;
                for (const auto& c : centres) {
                    const double d2 = (Eigen::Vector2d(col, row) - c).squaredNorm();
                    v -= 90 * std::exp(-d2 / (2 * 3.0 * 3.0));
                }
            }
            img.at<uint8_t>(col, row) = uint8_t(std::lround(std::clamp(v, 0.0, 255.0)));
        }
    }
    return img;
}

/// Random rectangles of random gray levels inside the image circle, box blurred.
CImage texturedImage(const UnifiedSphereCamera& camera, unsigned seed)
{
    mrpt::random::CRandomGenerator rng(seed);
    const int w = camera.width, h = camera.height;
    std::vector<double> t(size_t(w * h));
    for (double& v : t) v = rng.drawUniform(110.0, 146.0);
    for (int k = 0; k < w * h / 150; k++) {
        const int x0 = int(rng.drawUniform(0.0, w)), y0 = int(rng.drawUniform(0.0, h));
        const int rw = int(rng.drawUniform(4.0, 24.0)), rh = int(rng.drawUniform(4.0, 24.0));
        const double gray = rng.drawUniform(0.0, 255.0);
        for (int y = y0; y < std::min(h, y0 + rh); y++)
            for (int x = x0; x < std::min(w, x0 + rw); x++) t[size_t(y * w + x)] = gray;
    }
    CImage img(w, h, mrpt::img::CH_GRAY);
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            double s = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++)
                    s += t[size_t(std::clamp(y + dy, 0, h - 1) * w + std::clamp(x + dx, 0, w - 1))];
            const bool valid = camera.unproject(Eigen::Vector2d(x, y)).has_value();
            img.at<uint8_t>(x, y) = valid ? uint8_t(std::lround(s / 9)) : 0;
        }
    }
    return img;
}

/// The image turned by 90° about its centre (square images): (x, y) → (y, n − 1 − x).
CImage turned(const CImage& in)
{
    const int n = int(in.getWidth());
    CImage out(n, n, mrpt::img::CH_GRAY);
    for (int y = 0; y < n; y++)
        for (int x = 0; x < n; x++) out.at<uint8_t>(y, n - 1 - x) = in.at<uint8_t>(x, y);
    return out;
}

void expectSameFeatures(const TViewFeatures& a, const TViewFeatures& b)
{
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(a.rays, b.rays);
    EXPECT_EQ(a.scales, b.scales);
    EXPECT_EQ(a.laplacian_signs, b.laplacian_signs);
    EXPECT_EQ(a.descriptors, b.descriptors);
}

}  // namespace

// Blobs at 24 known directions (elevations 0° to 60°): each gives a point whose ray is within
// 0.2° of its direction (measured 0.11° at most), with the sign of a dark blob. (Blobs closer
// to the top and bottom edges of the image lose their descriptor window.)
TEST(OmniFeatureExtractor, FindsBlobsAtTheirDirections)
{
    const UnifiedSphereCamera camera = omniCamera();
    std::vector<Eigen::Vector3d> rays;
    for (int i = 0; i < 24; i++) {
        const double az = DEG2RAD(15.0 * i + 3.0), el = DEG2RAD(12.0 * (i % 6));
        rays.emplace_back(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    }
    const OmniFeatureExtractor fx(camera, Eigen::Matrix3d::Identity(), {});
    const TViewFeatures f = fx.extract(blobImage(camera, rays));
    EXPECT_GE(f.size(), rays.size());
    EXPECT_LE(f.size(), size_t(fx.options().max_features));
    double worst = 0;
    for (const auto& r : rays) {
        double best = M_PI;
        int8_t sign = 0;
        for (size_t k = 0; k < f.size(); k++) {
            const double a = angleBetween(r, f.rays.col(Eigen::Index(k)));
            if (a < best) best = a, sign = f.laplacian_signs[k];
        }
        worst = std::max(worst, best);
        EXPECT_EQ(sign, 1);
    }
    EXPECT_LT(mrpt::RAD2DEG(worst), 0.2);
    for (size_t k = 0; k < f.size(); k++) {
        EXPECT_NEAR(f.rays.col(Eigen::Index(k)).norm(), 1.0, 1e-12);
        EXPECT_GT(f.scales[k], 0.0f);
    }
}

// Deterministic, strongest first (max_features keeps a prefix), colour converted, and rays
// turned by the mounting rotation.
TEST(OmniFeatureExtractor, DeterministicPrefixColourAndMounting)
{
    const UnifiedSphereCamera camera = omniCamera();
    const CImage img = texturedImage(camera, 3);
    OmniFeatureExtractor::TOptions opt;
    const OmniFeatureExtractor fx(camera, Eigen::Matrix3d::Identity(), opt);
    const TViewFeatures a = fx.extract(img), b = fx.extract(img);
    expectSameFeatures(a, b);
    EXPECT_EQ(a.size(), size_t(opt.max_features));

    opt.max_features = 25;
    const TViewFeatures few =
        OmniFeatureExtractor(camera, Eigen::Matrix3d::Identity(), opt).extract(img);
    ASSERT_EQ(few.size(), 25u);
    for (size_t k = 0; k < few.size(); k++) {
        EXPECT_EQ(few.pixels.col(Eigen::Index(k)), a.pixels.col(Eigen::Index(k)));
        EXPECT_EQ(few.descriptors[k], a.descriptors[k]);
    }

    expectSameFeatures(fx.extract(img.colorImage()), a);

    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).matrix();
    const TViewFeatures turned_rays = OmniFeatureExtractor(camera, R, {}).extract(img);
    ASSERT_EQ(turned_rays.size(), a.size());
    EXPECT_EQ(turned_rays.pixels, a.pixels);
    EXPECT_EQ(turned_rays.descriptors, a.descriptors);
    EXPECT_LT((turned_rays.rays - R * a.rays).cwiseAbs().maxCoeff(), 1e-12);
}

// A turn of the robot by 90° turns the image by 90° about the zenith's pixel: the same points
// come back (measured: all 400 within 0.5 px) with the same oriented descriptors (median
// distance 0.0000), while upright SURF at the same points differs (median 0.84).
TEST(OmniFeatureExtractor, DescriptorIsInvariantToTheHeading)
{
    const UnifiedSphereCamera camera = squareCamera();
    const CImage img = texturedImage(camera, 4), img_turned = turned(img);
    const OmniFeatureExtractor fx(camera, Eigen::Matrix3d::Identity(), {});
    const TViewFeatures a = fx.extract(img), b = fx.extract(img_turned);
    ASSERT_GT(a.size(), 150u);
    const USurfDescriptor usurf_a(img), usurf_b(img_turned);
    const int n = camera.width;
    size_t found = 0;
    std::vector<double> oriented, upright;
    for (size_t k = 0; k < a.size(); k++) {
        const Eigen::Vector2f p = a.pixels.col(Eigen::Index(k));
        const Eigen::Vector2f q(p.y(), float(n - 1) - p.x());
        for (size_t j = 0; j < b.size(); j++) {
            if ((b.pixels.col(Eigen::Index(j)) - q).norm() > 0.5f) continue;
            found++;
            oriented.push_back(USurfDescriptor::distance(a.descriptors[k], b.descriptors[j]));
            const auto ua = usurf_a.compute(p.x(), p.y(), a.scales[k]);
            const auto ub = usurf_b.compute(q.x(), q.y(), b.scales[j]);
            if (ua && ub) upright.push_back(USurfDescriptor::distance(*ua, *ub));
            // The direction of the turned pixel (a turn about z), within the 0.5 px.
            const Eigen::Vector3d expected = *camera.unproject(q.cast<double>());
            EXPECT_LT(angleBetween(b.rays.col(Eigen::Index(j)), expected), DEG2RAD(0.5));
            break;
        }
    }
    EXPECT_GT(found, a.size() * 95 / 100);
    const auto median = [](std::vector<double> v) {
        std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
        return v[v.size() / 2];
    };
    ASSERT_GT(upright.size(), 50u);
    EXPECT_LT(median(oriented), 0.01);
    EXPECT_GT(median(upright), 0.5);
}

// With the image's axes, the oriented descriptor is U-SURF (core::USurfDescriptor).
TEST(OmniFeatureExtractor, OrientedDescriptorWithImageAxesIsUprightSurf)
{
    const UnifiedSphereCamera camera = omniCamera();
    const CImage img = texturedImage(camera, 5);
    const USurfDescriptor usurf(img);
    const mrpt_vslam::core::IntegralImage integral(img);
    mrpt::random::CRandomGenerator rng(6);
    int compared = 0;
    for (int i = 0; i < 200; i++) {
        const double x = rng.drawUniform(100.0, 540.0), y = rng.drawUniform(100.0, 380.0);
        const double s = rng.drawUniform(1.2, 3.5);
        // The whole window on the texture (inside the image circle).
        bool textured = true;
        for (const double dx : {-15 * s, 15 * s})
            for (const double dy : {-15 * s, 15 * s})
                textured = textured && camera.unproject(Eigen::Vector2d(x + dx, y + dy));
        if (!textured) continue;
        const auto oriented =
            OmniFeatureExtractor::orientedDescriptor(integral, x, y, s, Eigen::Vector2d(0, 1));
        const auto upright = usurf.compute(x, y, s);
        ASSERT_TRUE(oriented && upright);
        compared++;
        for (size_t k = 0; k < USurfDescriptor::kSize; k++)
            EXPECT_NEAR((*oriented)[k], (*upright)[k], 1e-5);
    }
    EXPECT_GT(compared, 100);
    // Too close to the border for the turned window.
    EXPECT_FALSE(OmniFeatureExtractor::orientedDescriptor(integral, 10, 200, 2.0,
                                                          Eigen::Vector2d(0.6, 0.8)));
}

TEST(OmniFeatureExtractor, RejectsBadInput)
{
    const UnifiedSphereCamera camera = omniCamera();
    const OmniFeatureExtractor fx(camera, Eigen::Matrix3d::Identity(), {});
    try {
        fx.extract(CImage(320, 240, mrpt::img::CH_GRAY));
        ADD_FAILURE() << "wrong size accepted";
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("320x240"), std::string::npos) << what;
        EXPECT_NE(what.find("640x480"), std::string::npos) << what;
    }
    EXPECT_THROW(OmniFeatureExtractor(camera, 2 * Eigen::Matrix3d::Identity(), {}),
                 std::invalid_argument);
    EXPECT_THROW(OmniFeatureExtractor(camera, -Eigen::Matrix3d::Identity(), {}),
                 std::invalid_argument);
    UnifiedSphereCamera bad = camera;
    bad.fx = -1;
    EXPECT_THROW(OmniFeatureExtractor(bad, Eigen::Matrix3d::Identity(), {}), std::invalid_argument);
}

TEST(OmniFeatureExtractor, OptionsFromIniAndValidation)
{
    mrpt::config::CConfigFileMemory ini;
    ini.write("F", "hessian_threshold", 25.0);
    ini.write("F", "octaves", 2);
    ini.write("F", "initial_step", 1);
    ini.write("F", "max_features", 250);
    ini.write("F", "window_margin", 0.75);
    OmniFeatureExtractor::TOptions o;
    o.loadFromConfigFile(ini, "F");
    EXPECT_DOUBLE_EQ(o.detector.hessian_threshold, 25.0);
    EXPECT_EQ(o.detector.octaves, 2);
    EXPECT_EQ(o.detector.initial_step, 1);
    EXPECT_EQ(o.max_features, 250);
    EXPECT_DOUBLE_EQ(o.window_margin, 0.75);

    mrpt::config::CConfigFileMemory saved;
    o.saveToConfigFile(saved, "F");
    std::string text;
    saved.getContent(text);
    OmniFeatureExtractor::TOptions back;
    back.loadFromConfigFile(mrpt::config::CConfigFileMemory(text), "F");
    EXPECT_DOUBLE_EQ(back.detector.hessian_threshold, 25.0);
    EXPECT_EQ(back.detector.octaves, 2);
    EXPECT_EQ(back.max_features, 250);
    EXPECT_DOUBLE_EQ(back.window_margin, 0.75);

    for (const auto& [key, value] :
         std::vector<std::pair<std::string, double>>{{"max_features", 0},
                                                     {"window_margin", 1.5},
                                                     {"octaves", 0},
                                                     {"initial_step", 0},
                                                     {"hessian_threshold", -1}}) {
        mrpt::config::CConfigFileMemory b;
        b.write("F", key, value);
        try {
            OmniFeatureExtractor::TOptions t;
            t.loadFromConfigFile(b, "F");
            ADD_FAILURE() << key << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    }
}
