#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/UnifiedSphereCamera.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

using mrpt_vslam::core::UnifiedSphereCamera;

namespace {

/// Cameras covering the model's regimes: hyperbolic (default), with skew and fx ≠ fy,
/// parabolic, pinhole, and ξ > 1 (wide-angle lens).
std::vector<UnifiedSphereCamera> testCameras()
{
    std::vector<UnifiedSphereCamera> cams(5);
    cams[1].fx = 118;
    cams[1].fy = 104;
    cams[1].skew = 3.5;
    cams[1].cx = 317.25;
    cams[1].cy = 243.5;
    cams[2].xi = 1.0;
    cams[2].fx = cams[2].fy = 70;
    cams[2].max_theta = mrpt::DEG2RAD(140.0);
    cams[3].xi = 0.0;
    cams[3].fx = cams[3].fy = 300;
    cams[3].max_theta = mrpt::DEG2RAD(60.0);
    cams[4].xi = 1.6;
    cams[4].fx = cams[4].fy = 300;
    cams[4].max_theta = mrpt::DEG2RAD(115.0);  // limit acos(−1/1.6) = 128.7°
    for (const auto& cam : cams) cam.validate();
    return cams;
}

/// Normalised radius ρ(θ) = sin θ / (cos θ + ξ) of the unified model.
double normalisedRadius(double theta, double xi)
{
    return std::sin(theta) / (std::cos(theta) + xi);
}

Eigen::Vector3d rayOf(double azimuth, double theta)
{
    return {std::sin(theta) * std::cos(azimuth), std::sin(theta) * std::sin(azimuth),
            std::cos(theta)};
}

}  // namespace

TEST(UnifiedSphereCamera, PixelRayPixelRoundTripOverTheWholeImage)
{
    for (const auto& cam : testCameras()) {
        size_t valid = 0, expected_valid = 0;
        double worst = 0;
        for (int row = 0; row < cam.height; row++) {
            for (int col = 0; col < cam.width; col++) {
                const Eigen::Vector2d px(col + 0.25, row + 0.5);
                const auto ray = cam.unproject(px);
                // Expected validity from the closed-form ρ(max_theta) (skew-free inverse of K).
                const double my = (px.y() - cam.cy) / cam.fy;
                const double mx = (px.x() - cam.cx - cam.skew * my) / cam.fx;
                const double rho_max = normalisedRadius(cam.max_theta, cam.xi);
                const double rho = std::hypot(mx, my);
                const bool inside = px.x() <= cam.width - 1 && px.y() <= cam.height - 1;
                // Skip the rounding band at the rim.
                if (std::abs(rho - rho_max) < 1e-9 * rho_max) continue;
                if (inside && rho < rho_max) expected_valid++;
                EXPECT_EQ(ray.has_value(), inside && rho < rho_max) << col << "," << row;
                if (!ray) continue;
                valid++;
                EXPECT_NEAR(ray->norm(), 1.0, 1e-12);
                const auto back = cam.project(*ray);
                ASSERT_TRUE(back.has_value()) << col << "," << row;
                worst = std::max(worst, (*back - px).norm());
            }
        }
        EXPECT_EQ(valid, expected_valid);
        EXPECT_GT(valid, size_t(100000)) << "xi=" << cam.xi;
        EXPECT_LT(worst, 1e-9) << "xi=" << cam.xi;
    }
}

TEST(UnifiedSphereCamera, RayPixelRayRoundTrip)
{
    mrpt::random::CRandomGenerator rng(3);
    for (const auto& cam : testCameras()) {
        size_t visible = 0;
        double worst = 0;
        for (int k = 0; k < 200000; k++) {
            // Uniform on the sphere.
            const double z = rng.drawUniform(-1.0, 1.0), azimuth = rng.drawUniform(-M_PI, M_PI);
            const Eigen::Vector3d ray = rayOf(azimuth, std::acos(z));
            const auto px = cam.project(2.5 * ray);  // any length
            if (std::acos(z) > cam.max_theta) {
                EXPECT_FALSE(px.has_value());
                continue;
            }
            if (!px) continue;  // outside the image rectangle
            visible++;
            const auto back = cam.unproject(*px);
            ASSERT_TRUE(back.has_value());
            worst = std::max(worst, (*back - ray).norm());
        }
        EXPECT_GT(visible, size_t(10000)) << "xi=" << cam.xi;
        EXPECT_LT(worst, 1e-9) << "xi=" << cam.xi;
    }
}

TEST(UnifiedSphereCamera, ReducesToPinholeWhenXiIsZero)
{
    UnifiedSphereCamera cam;
    cam.xi = 0;
    cam.fx = 500;
    cam.fy = 480;
    cam.skew = 2;
    cam.max_theta = mrpt::DEG2RAD(80.0);
    cam.width = 2000;
    cam.height = 2000;
    cam.cx = 1000;
    cam.cy = 990;
    const Eigen::Vector3d p(0.7, -0.4, 2.0);
    const auto uv = cam.project(p);
    ASSERT_TRUE(uv.has_value());
    EXPECT_NEAR(uv->x(), 500 * 0.35 + 2 * -0.2 + 1000, 1e-9);
    EXPECT_NEAR(uv->y(), 480 * -0.2 + 990, 1e-9);
    const auto ray = cam.unproject(*uv);
    ASSERT_TRUE(ray.has_value());
    EXPECT_LT((*ray - p.normalized()).norm(), 1e-12);
    // Behind the image plane: not visible.
    EXPECT_FALSE(cam.project(Eigen::Vector3d(0.1, 0, -1)).has_value());
}

TEST(UnifiedSphereCamera, AxisMapsToThePrincipalPoint)
{
    for (const auto& cam : testCameras()) {
        const auto uv = cam.project(Eigen::Vector3d(0, 0, 3));
        ASSERT_TRUE(uv.has_value());
        EXPECT_NEAR(uv->x(), cam.cx, 1e-12);
        EXPECT_NEAR(uv->y(), cam.cy, 1e-12);
        const auto ray = cam.unproject(Eigen::Vector2d(cam.cx, cam.cy));
        ASSERT_TRUE(ray.has_value());
        EXPECT_NEAR(ray->z(), 1.0, 1e-15);
    }
}

TEST(UnifiedSphereCamera, KnownAnglesMapToClosedFormRadii)
{
    UnifiedSphereCamera cam;  // ξ = 0.9, fx = fy = 110
    // Horizon (θ = 90°): ρ = 1/ξ, for every azimuth.
    for (double azimuth = -3; azimuth < 3.2; azimuth += 0.5) {
        const auto uv = cam.project(rayOf(azimuth, M_PI / 2));
        ASSERT_TRUE(uv.has_value());
        EXPECT_NEAR(uv->x(), cam.cx + 110 / 0.9 * std::cos(azimuth), 1e-9);
        EXPECT_NEAR(uv->y(), cam.cy + 110 / 0.9 * std::sin(azimuth), 1e-9);
    }
    // 60° from the axis: ρ = sin 60° / (cos 60° + ξ) = (√3/2) / 1.4.
    const auto uv60 = cam.project(rayOf(0, M_PI / 3));
    ASSERT_TRUE(uv60.has_value());
    EXPECT_NEAR(uv60->x() - cam.cx, 110 * std::sqrt(3.0) / 2 / 1.4, 1e-9);
    // The rim of the default camera, 120°: ρ = (√3/2) / 0.4 → 238.2 px, inside the 480 rows.
    const auto rim = cam.project(rayOf(M_PI / 2, cam.max_theta - 1e-12));
    ASSERT_TRUE(rim.has_value());
    EXPECT_NEAR(rim->y() - cam.cy, 110 * std::sqrt(3.0) / 2 / 0.4, 1e-9);
    EXPECT_NEAR(rim->y() - cam.cy, 238.16, 0.01);
    EXPECT_FALSE(cam.project(rayOf(M_PI / 2, cam.max_theta + 1e-6)).has_value());
    EXPECT_FALSE(cam.project(Eigen::Vector3d::Zero()).has_value());
    // Parabolic mirror: ρ = tan(θ/2).
    cam.xi = 1;
    cam.fx = cam.fy = 100;
    const auto uv_par = cam.project(rayOf(M_PI, 1.2));
    ASSERT_TRUE(uv_par.has_value());
    EXPECT_NEAR(uv_par->x(), cam.cx - 100 * std::tan(0.6), 1e-9);
    EXPECT_NEAR(uv_par->y(), cam.cy, 1e-9);
    // Outside the image rectangle.
    EXPECT_FALSE(cam.unproject(Eigen::Vector2d(-0.01, 100)).has_value());
    EXPECT_FALSE(cam.unproject(Eigen::Vector2d(10, cam.height - 0.99)).has_value());
}

TEST(UnifiedSphereCamera, ModelLimit)
{
    UnifiedSphereCamera cam;
    cam.xi = 0;
    EXPECT_NEAR(cam.modelLimit(), M_PI / 2, 1e-15);
    cam.xi = 1;
    EXPECT_NEAR(cam.modelLimit(), M_PI, 1e-15);
    cam.xi = 0.5;
    EXPECT_NEAR(cam.modelLimit(), 2 * M_PI / 3, 1e-15);
    cam.xi = 2;
    EXPECT_NEAR(cam.modelLimit(), 2 * M_PI / 3, 1e-15);
    // ρ(θ) peaks at the limit for ξ > 1 (dρ/dθ ∝ 1 + ξ cos θ).
    const double lim = cam.modelLimit();
    EXPECT_GT(normalisedRadius(lim, 2), normalisedRadius(lim - 0.01, 2));
    EXPECT_GT(normalisedRadius(lim, 2), normalisedRadius(lim + 0.01, 2));
}

TEST(UnifiedSphereCamera, ProjectJacobianMatchesCentralDifferences)
{
    const double h = 1e-6;
    for (const auto& cam : testCameras()) {
        mrpt::random::CRandomGenerator rng(5);
        int checked = 0;
        for (int k = 0; k < 300; k++) {
            const double theta = rng.drawUniform(0.0, cam.max_theta - 1e-3);
            const Eigen::Vector3d p =
                rng.drawUniform(0.5, 4.0) * rayOf(rng.drawUniform(-M_PI, M_PI), theta);
            const auto J = cam.projectJacobian(p);
            for (int i = 0; i < 3; i++) {
                Eigen::Vector3d dp = Eigen::Vector3d::Zero();
                dp[i] = h;
                const auto plus = cam.project(p + dp), minus = cam.project(p - dp);
                if (!plus || !minus) continue;  // outside the image rectangle
                const Eigen::Vector2d numeric = (*plus - *minus) / (2 * h);
                EXPECT_LT((J.col(i) - numeric).norm(), 1e-5 * (1 + numeric.norm()))
                    << "xi=" << cam.xi << " theta=" << theta << " i=" << i;
                checked++;
            }
        }
        EXPECT_GT(checked, 600) << "xi=" << cam.xi;
    }
}

TEST(UnifiedSphereCamera, LoadsAndSavesIni)
{
    mrpt::config::CConfigFileMemory ini(
        "[OMNICAM]\n"
        "xi = 0.82\n"
        "fx = 121.5\n"
        "fy = 119\n"
        "cx = 401\n"
        "cy = 299.5\n"
        "skew = 0.3\n"
        "width = 800\n"
        "height = 600\n"
        "max_theta_deg = 110\n");
    UnifiedSphereCamera cam;
    cam.loadFromConfigFile(ini, "OMNICAM");
    EXPECT_DOUBLE_EQ(cam.xi, 0.82);
    EXPECT_DOUBLE_EQ(cam.fx, 121.5);
    EXPECT_DOUBLE_EQ(cam.fy, 119.0);
    EXPECT_DOUBLE_EQ(cam.cx, 401.0);
    EXPECT_DOUBLE_EQ(cam.cy, 299.5);
    EXPECT_DOUBLE_EQ(cam.skew, 0.3);
    EXPECT_EQ(cam.width, 800);
    EXPECT_EQ(cam.height, 600);
    EXPECT_NEAR(cam.max_theta, mrpt::DEG2RAD(110.0), 1e-12);

    mrpt::config::CConfigFileMemory saved;
    cam.saveToConfigFile(saved, "CAM");
    std::string text;
    saved.getContent(text);
    UnifiedSphereCamera reread;
    reread.loadFromConfigFile(mrpt::config::CConfigFileMemory(text), "CAM");
    EXPECT_DOUBLE_EQ(reread.xi, cam.xi);
    EXPECT_DOUBLE_EQ(reread.fy, cam.fy);
    EXPECT_DOUBLE_EQ(reread.skew, cam.skew);
    EXPECT_EQ(reread.height, cam.height);
    EXPECT_NEAR(reread.max_theta, cam.max_theta, 1e-7);
}

TEST(UnifiedSphereCamera, RejectsBadParametersNamingTheKey)
{
    EXPECT_NO_THROW(UnifiedSphereCamera().validate());
    const auto expectInvalid = [](const std::string& key_values, const std::string& key) {
        mrpt::config::CConfigFileMemory ini("[cam]\n" + key_values);
        UnifiedSphereCamera cam;
        try {
            cam.loadFromConfigFile(ini, "cam");
            ADD_FAILURE() << "accepted: " << key_values;
        } catch (const std::invalid_argument& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(key + " = "), std::string::npos) << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    };
    expectInvalid("xi = -0.1\n", "xi");
    expectInvalid("xi = nan\n", "xi");
    expectInvalid("fx = 0\n", "fx");
    expectInvalid("fy = -100\n", "fy");
    expectInvalid("cx = inf\n", "cx");
    expectInvalid("skew = nan\n", "skew");
    expectInvalid("width = 0\n", "width");
    expectInvalid("height = -1\n", "height");
    expectInvalid("max_theta_deg = 0\n", "max_theta_deg");
    // ξ = 0.9: the model folds back at acos(−0.9) = 154.2°.
    expectInvalid("max_theta_deg = 155\n", "max_theta_deg");
    // Pinhole: at most 90°.
    expectInvalid("xi = 0\nmax_theta_deg = 90\n", "max_theta_deg");
    // ξ = 2: limit acos(−1/2) = 120°.
    expectInvalid("xi = 2\nmax_theta_deg = 121\n", "max_theta_deg");
    UnifiedSphereCamera ok;
    ok.xi = 2;
    ok.max_theta = mrpt::DEG2RAD(119.0);
    EXPECT_NO_THROW(ok.validate());
}
