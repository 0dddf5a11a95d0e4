#include <gtest/gtest.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt_vslam/sim/SportsHallScenario.h>

#include <cmath>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "TestConfig.h"

using namespace mrpt_vslam::sim;

namespace {

struct TBlob {
    Eigen::Vector2d centroid;
    int area;
};

/// Bright blobs of at least `min_area` pixels: threshold + connected components (8-connected).
std::vector<TBlob> brightBlobs(const mrpt::img::CImage& image, int threshold, int min_area)
{
    cv::Mat binary, labels, stats, centroids;
    cv::threshold(image.asCvMatRef(), binary, threshold, 255, cv::THRESH_BINARY);
    const int n = cv::connectedComponentsWithStats(binary, labels, stats, centroids, 8);
    std::vector<TBlob> blobs;
    for (int i = 1; i < n; i++) {
        const int area = stats.at<int>(i, cv::CC_STAT_AREA);
        if (area >= min_area)
            blobs.push_back({{centroids.at<double>(i, 0), centroids.at<double>(i, 1)}, area});
    }
    return blobs;
}

/// The hall's camera, detector and renderer, loaded from the shipped config.
struct THallCamera {
    THallCamera()
    {
        hall.loadConfig(test::sportsHallConfig());
        hall.detections.reset(7);
        hall.renderer.reset(8);
        model = std::make_unique<PajdlaBaksteinInverse>(hall.camera);
    }
    TFrameDetections observe(int frame)
    {
        const auto poses = hall.trajectory.generate(frame + 1);
        const mrpt::poses::CPose3D robot(mrpt::poses::CPose2D(poses.back()));
        return hall.detections.simulate(robot + hall.camera_on_robot, hall.lights, frame, *model);
    }
    SportsHallScenario hall;
    std::unique_ptr<PajdlaBaksteinInverse> model;
};

}  // namespace

TEST(LightBlobRenderer, BlobCentroidsMatchTheProjectionsOfTheLightCentres)
{
    THallCamera cam;
    auto& hall = cam.hall;
    const auto& model = cam.model;
    hall.detections.spurious_rate = 0;
    hall.renderer.hot_pixel_fraction = 0;
    double sum = 0, worst = 0;
    int count = 0;
    for (int frame = 0; frame < 320; frame += 16) {
        const TFrameDetections obs = cam.observe(frame);
        const std::vector<TBlob> blobs =
            brightBlobs(hall.renderer.render(obs, hall.lights.radius, *model), 100, 2);
        ASSERT_EQ(blobs.size(), obs.lights.size()) << "frame " << frame;
        for (const TVisibleLight& light : obs.lights) {
            double best = 1e9;
            for (const TBlob& b : blobs) best = std::min(best, (b.centroid - light.uv).norm());
            sum += best;
            worst = std::max(worst, best);
            count++;
        }
    }
    std::cout << "centroid - projection error over " << count << " blobs: mean " << sum / count
              << " px, max " << worst << " px\n";
    EXPECT_GT(count, 100);
    EXPECT_LT(sum / count, 0.3);
    EXPECT_LT(worst, 1.0);
}

TEST(LightBlobRenderer, BlobsSaturateAndTheBackgroundStaysSparse)
{
    THallCamera cam;
    auto& hall = cam.hall;
    const auto& model = cam.model;
    hall.detections.spurious_rate = 0;
    const TFrameDetections obs = cam.observe(0);
    const mrpt::img::CImage image = hall.renderer.render(obs, hall.lights.radius, *model);
    ASSERT_EQ(image.getWidth(), 640u);
    ASSERT_EQ(image.getHeight(), 480u);
    ASSERT_FALSE(image.isColor());
    const cv::Mat& m = image.asCvMatRef();
    double max_value = 0;
    cv::minMaxLoc(m, nullptr, &max_value);
    EXPECT_EQ(max_value, 255.0);
    const double non_zero = cv::countNonZero(m) / static_cast<double>(m.total());
    EXPECT_GT(non_zero, 0.001);
    EXPECT_LT(non_zero, 0.02);
}

TEST(LightBlobRenderer, SpuriousReflectionsAreRenderedWhereReported)
{
    THallCamera cam;
    auto& hall = cam.hall;
    const auto& model = cam.model;
    TFrameDetections obs;
    obs.spurious.push_back({{200.3, 150.6}, 2.0, 250});
    hall.renderer.hot_pixel_fraction = 0;
    const std::vector<TBlob> blobs =
        brightBlobs(hall.renderer.render(obs, hall.lights.radius, *model), 60, 2);
    ASSERT_EQ(blobs.size(), 1u);
    EXPECT_NEAR(blobs[0].centroid.x(), 200.3, 0.3);
    EXPECT_NEAR(blobs[0].centroid.y(), 150.6, 0.3);
}
