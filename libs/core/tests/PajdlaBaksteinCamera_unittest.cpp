#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/math/num_jacobian.h>
#include <mrpt_vslam/core/PajdlaBaksteinCamera.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

using mrpt_vslam::core::PajdlaBaksteinCamera;

TEST(PajdlaBaksteinCamera, ProjectJacobianMatchesNumeric)
{
    PajdlaBaksteinCamera cam;
    cam.beta = 1.1;  // exercise the β row scaling
    const std::function<void(const Eigen::Vector2d&, const PajdlaBaksteinCamera&, Eigen::Vector2d&)>
        f = [](const Eigen::Vector2d& x, const PajdlaBaksteinCamera& c, Eigen::Vector2d& out) {
            out = c.project(x[0], x[1]);
        };
    const Eigen::Vector2d increments(1e-6, 1e-6);
    int checked = 0;
    for (double phi = -3.1; phi < 3.14; phi += 0.37) {
        for (double theta = 0.05; theta < cam.max_theta; theta += 0.11) {
            const Eigen::Vector2d x(phi, theta);
            Eigen::Matrix2d numeric;
            mrpt::math::estimateJacobian(x, f, increments, cam, numeric);
            const Eigen::Matrix2d analytic = cam.projectJacobian(phi, theta);
            EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff(), 1e-5)
                << "phi=" << phi << " theta=" << theta << "\n"
                << analytic << "\n"
                << numeric;
            checked++;
        }
    }
    EXPECT_EQ(checked, 17 * 14);
}

TEST(PajdlaBaksteinCamera, RadiusIsMonotonicWithMatchingDerivative)
{
    const PajdlaBaksteinCamera cam;
    EXPECT_EQ(cam.radius(0.0), 0.0);
    // Closed form of dr/dθ at 0: a/b + c/d.
    EXPECT_NEAR(cam.radiusDerivative(0.0), cam.a / cam.b + cam.c / cam.d, 1e-12);
    constexpr int kSteps = 2000;
    double prev = cam.radius(0.0);
    for (int i = 1; i <= kSteps; i++) {
        const double theta = cam.max_theta * i / kSteps;
        const double r = cam.radius(theta);
        EXPECT_GT(r, prev) << theta;
        prev = r;
        const double h = 1e-6;
        const double numeric = (cam.radius(theta + h) - cam.radius(theta - h)) / (2 * h);
        EXPECT_NEAR(cam.radiusDerivative(theta), numeric, 1e-4) << theta;
    }
    // Image circle of the default camera at 89 deg: ≈ 244 px, inside the 640-px width.
    EXPECT_NEAR(cam.radius(cam.max_theta), 244.3, 0.5);
}

TEST(PajdlaBaksteinCamera, AnglesOfPointClosedForms)
{
    using mrpt::math::TPoint3D;
    const auto angles = [](double x, double y, double z) {
        return PajdlaBaksteinCamera::anglesOfPoint(TPoint3D(x, y, z));
    };
    EXPECT_NEAR(angles(0, 0, 2).y(), 0.0, 1e-15);  // on the optical axis
    EXPECT_NEAR(angles(3, 0, 0).x(), 0.0, 1e-15);
    EXPECT_NEAR(angles(3, 0, 0).y(), M_PI / 2, 1e-15);
    EXPECT_NEAR(angles(0, 1, 1).x(), M_PI / 2, 1e-15);
    EXPECT_NEAR(angles(0, 1, 1).y(), M_PI / 4, 1e-15);
    EXPECT_NEAR(angles(-1, 0, -1).x(), M_PI, 1e-15);
    EXPECT_NEAR(angles(-1, 0, -1).y(), 3 * M_PI / 4, 1e-15);
    EXPECT_NEAR(angles(1, -1, std::sqrt(2.0)).x(), -M_PI / 4, 1e-15);
    EXPECT_NEAR(angles(1, -1, std::sqrt(2.0)).y(), M_PI / 4, 1e-15);
    EXPECT_NEAR(angles(1, std::sqrt(3.0), 0.0).x(), M_PI / 3, 1e-15);

    // A point along the ray (φ, θ) projects back to those angles.
    const double phi = -2.2, theta = 1.1;
    const Eigen::Vector2d back = PajdlaBaksteinCamera::anglesOfPoint(
        TPoint3D(5 * std::sin(theta) * std::cos(phi), 5 * std::sin(theta) * std::sin(phi),
                 5 * std::cos(theta)));
    EXPECT_NEAR(back.x(), phi, 1e-12);
    EXPECT_NEAR(back.y(), theta, 1e-12);
}

TEST(PajdlaBaksteinCamera, ProjectFollowsEquationOne)
{
    PajdlaBaksteinCamera cam;
    cam.beta = 1.2;
    // φ = π/2: u = u0, v = β (v0 + r).
    const double r = cam.radius(0.8);
    const Eigen::Vector2d uv = cam.project(M_PI / 2, 0.8);
    EXPECT_NEAR(uv.x(), cam.u0, 1e-9);
    EXPECT_NEAR(uv.y(), 1.2 * (cam.v0 + r), 1e-9);
    EXPECT_TRUE(cam.isVisible(0.3, 0.2));
    EXPECT_FALSE(cam.isVisible(0.3, cam.max_theta + 0.01));
    EXPECT_FALSE(cam.isVisible(0.3, -0.01));
    EXPECT_FALSE(cam.isInsideImage(Eigen::Vector2d(-0.1, 10)));
    EXPECT_TRUE(cam.isInsideImage(Eigen::Vector2d(cam.width - 1, cam.height - 1)));
}

TEST(PajdlaBaksteinCamera, LoadsFromIniText)
{
    mrpt::config::CConfigFileMemory ini(
        "[OMNICAM]\n"
        "a = 140.5\n"
        "b = 2.7\n"
        "c = 170\n"
        "d = 1.9\n"
        "u0 = 330.25\n"
        "v0 = 235.5\n"
        "beta = 1.02\n"
        "width = 800\n"
        "height = 600\n"
        "max_theta_deg = 85\n");
    PajdlaBaksteinCamera cam;
    cam.loadFromConfigFile(ini, "OMNICAM");
    EXPECT_DOUBLE_EQ(cam.a, 140.5);
    EXPECT_DOUBLE_EQ(cam.b, 2.7);
    EXPECT_DOUBLE_EQ(cam.c, 170.0);
    EXPECT_DOUBLE_EQ(cam.d, 1.9);
    EXPECT_DOUBLE_EQ(cam.u0, 330.25);
    EXPECT_DOUBLE_EQ(cam.v0, 235.5);
    EXPECT_DOUBLE_EQ(cam.beta, 1.02);
    EXPECT_EQ(cam.width, 800);
    EXPECT_EQ(cam.height, 600);
    EXPECT_NEAR(cam.max_theta, mrpt::DEG2RAD(85.0), 1e-12);

    // Save → text → load round trip, as a saved .ini file is read back.
    mrpt::config::CConfigFileMemory saved;
    cam.saveToConfigFile(saved, "CAM");
    std::string text;
    saved.getContent(text);
    PajdlaBaksteinCamera reread;
    reread.loadFromConfigFile(mrpt::config::CConfigFileMemory(text), "CAM");
    EXPECT_DOUBLE_EQ(reread.a, cam.a);
    EXPECT_DOUBLE_EQ(reread.d, cam.d);
    EXPECT_DOUBLE_EQ(reread.u0, cam.u0);
    EXPECT_EQ(reread.width, cam.width);
    EXPECT_NEAR(reread.max_theta, cam.max_theta, 1e-7);
}

TEST(PajdlaBaksteinCamera, ValidateRejectsImpossibleParametersNamingKeyAndValue)
{
    EXPECT_NO_THROW(PajdlaBaksteinCamera().validate());
    const auto expectInvalid = [](const char* key_values, const std::string& message) {
        mrpt::config::CConfigFileMemory ini(std::string("[cam]\n") + key_values);
        PajdlaBaksteinCamera cam;
        try {
            cam.loadFromConfigFile(ini, "cam");
            ADD_FAILURE() << key_values << " accepted";
        } catch (const std::invalid_argument& e) {
            EXPECT_EQ(std::string(e.what()), "PajdlaBaksteinCamera: " + message) << key_values;
        }
    };
    expectInvalid("b = 0\n", "b = 0 must be > 0");
    expectInvalid("b = -2.5\n", "b = -2.5 must be > 0");
    expectInvalid("d = 0\n", "d = 0 must be > 0");
    expectInvalid("beta = 0\n", "beta = 0 must be > 0");
    expectInvalid("width = 0\n", "width = 0 must be > 0");
    expectInvalid("height = -1\n", "height = -1 must be > 0");
    expectInvalid("max_theta_deg = 0\n", "max_theta_deg = 0 must be in (0, 180)");
    expectInvalid("max_theta_deg = 180\n", "max_theta_deg = 180 must be in (0, 180)");
    // tan(θ/b) diverges at θ = b·90 deg = 45 deg for b = 0.5.
    expectInvalid("b = 0.5\nmax_theta_deg = 60\n",
                  "max_theta_deg = 60 must be below b * 90 = 45 (the tan term diverges there)");
    // dr/dθ(0) = a/b + c/d = 60 − 200 < 0: r decreases near the axis.
    const PajdlaBaksteinCamera defaults;
    expectInvalid("c = -360\n", mrpt::format("max_theta_deg = %g is past the angle where "
                                             "r(theta) stops increasing",
                                             mrpt::RAD2DEG(defaults.max_theta)));
    // Increasing at 0 but turning back before max_theta (sin term past its peak at θ = d·90°).
    expectInvalid("a = 5\nc = 300\nd = 0.8\nmax_theta_deg = 100\n",
                  "max_theta_deg = 100 is past the angle where r(theta) stops increasing");
}
