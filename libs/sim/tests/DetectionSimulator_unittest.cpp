#include <gtest/gtest.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/sim/SportsHallScenario.h>

#include <cmath>
#include <iostream>

#include "TestConfig.h"

using namespace mrpt_vslam::sim;

namespace {

struct TRunStats {
    std::vector<double> err_phi, err_theta;  ///< normalised: angle error · dr / σ_px
    size_t frames = 0, spurious = 0, washed_out_seen = 0, lights_13_14_seen = 0;
};

TRunStats simulateHall()
{
    SportsHallScenario hall;
    hall.loadConfig(test::sportsHallConfig());
    hall.detections.reset(3);
    const PajdlaBaksteinInverse model(hall.camera);
    const auto& cam = hall.camera;
    TRunStats st;
    const auto poses = hall.trajectory.generate(hall.trajectory.frames);
    const auto lights = hall.lights.lights();
    for (size_t k = 0; k < poses.size(); k++) {
        const double t = static_cast<double>(k);
        const mrpt::poses::CPose3D camera =
            mrpt::poses::CPose3D(mrpt::poses::CPose2D(poses[k])) + hall.camera_on_robot;
        const TFrameDetections obs = hall.detections.simulate(camera, hall.lights, t, model);
        EXPECT_EQ(obs.bearings.size(), obs.lights.size() + obs.spurious.size());
        st.frames++;
        st.spurious += obs.spurious.size();
        for (size_t i = 0; i < obs.lights.size(); i++) {
            const TBearing& b = obs.bearings[i];
            EXPECT_EQ(b.source_id, obs.lights[i].id);
            const auto& light = lights[static_cast<size_t>(b.source_id - 1)];
            if (hall.lights.isWashedOut(light, t)) st.washed_out_seen++;
            if (b.source_id >= 13) st.lights_13_14_seen++;
            // Ground-truth geometry: direction of the light centre from the camera.
            const Eigen::Vector2d truth = mrpt_vslam::core::PajdlaBaksteinCamera::anglesOfPoint(
                camera.inverseComposePoint(light.position));
            EXPECT_LE(truth.y(), hall.detections.max_light_theta);
            st.err_phi.push_back(std::remainder(b.phi - truth.x(), 2 * M_PI) *
                                 cam.radius(truth.y()) / hall.detections.pixel_std);
            st.err_theta.push_back((b.theta - truth.y()) * cam.radiusDerivative(truth.y()) /
                                   hall.detections.pixel_std);
        }
        for (size_t i = obs.lights.size(); i < obs.bearings.size(); i++)
            EXPECT_EQ(obs.bearings[i].source_id, -1);
    }
    return st;
}

void meanStd(const std::vector<double>& v, double& mean, double& std)
{
    mean = 0;
    for (double x : v) mean += x;
    mean /= static_cast<double>(v.size());
    double var = 0;
    for (double x : v) var += (x - mean) * (x - mean);
    std = std::sqrt(var / static_cast<double>(v.size() - 1));
}

}  // namespace

TEST(DetectionSimulator, BearingErrorsMatchTheConfiguredPixelNoise)
{
    const TRunStats st = simulateHall();
    ASSERT_GT(st.err_phi.size(), 1500u);
    double m_phi, s_phi, m_theta, s_theta;
    meanStd(st.err_phi, m_phi, s_phi);
    meanStd(st.err_theta, m_theta, s_theta);
    std::cout << st.err_phi.size() << " light bearings; normalised error phi " << m_phi << " ± "
              << s_phi << ", theta " << m_theta << " ± " << s_theta << "\n";
    EXPECT_NEAR(m_phi, 0.0, 0.1);
    EXPECT_NEAR(m_theta, 0.0, 0.1);
    EXPECT_NEAR(s_phi, 1.0, 0.1);
    EXPECT_NEAR(s_theta, 1.0, 0.1);
}

TEST(DetectionSimulator, WashedOutLightsAreNeverReported)
{
    const TRunStats st = simulateHall();
    EXPECT_EQ(st.washed_out_seen, 0u);
    EXPECT_GT(st.lights_13_14_seen, 20u);
}

TEST(DetectionSimulator, SpuriousReflectionsFollowTheConfiguredRate)
{
    const TRunStats st = simulateHall();
    // Poisson(0.3) over 320 frames: mean 96, std ≈ 10.
    EXPECT_GT(st.spurious, 66u);
    EXPECT_LT(st.spurious, 126u);
}
