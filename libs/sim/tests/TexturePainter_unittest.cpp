#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt_vslam/sim/TexturePainter.h>

#include <algorithm>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "TestConfig.h"

using namespace mrpt_vslam::sim;

namespace {

TexturePainter shippedPainter()
{
    TexturePainter p;
    p.loadFromConfigFile(test::officeTeamConfig(), "Textures");
    return p;
}

TPaintedTexture paint(TSurfaceKind kind, double width, double height, uint32_t seed,
                      std::vector<TWallSpan> doors = {}, std::vector<TWallSpan> keep_clear = {})
{
    mrpt::random::CRandomGenerator rng(seed);
    return shippedPainter().paint({kind, width, height, doors, keep_clear}, rng);
}

/** Fraction of `corners` that a corner detector finds within 1 texel: Shi-Tomasi features
 *  (whose response peaks a few texels inside a corner's angle) refined with cornerSubPix. */
double fractionFoundByADetector(const TPaintedTexture& t)
{
    std::vector<cv::Point2f> features;
    cv::goodFeaturesToTrack(t.image.asCvMatRef(), features, 20000, 0.02, 3, cv::noArray(), 7);
    cv::cornerSubPix(t.image.asCvMatRef(), features, cv::Size(5, 5), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-3));
    size_t found = 0;
    for (const Eigen::Vector2d& c : t.corners) {
        // Corners are at texel edges; OpenCV puts texel centres at integers.
        const cv::Point2f p(static_cast<float>(c.x() * t.pixels_per_metre - 0.5),
                            static_cast<float>(c.y() * t.pixels_per_metre - 0.5));
        found += std::any_of(features.begin(), features.end(),
                             [&](const cv::Point2f& f) { return cv::norm(f - p) <= 1.0; });
    }
    return t.corners.empty() ? 0.0 : static_cast<double>(found) / t.corners.size();
}

}  // namespace

TEST(TexturePainter, DesignedCornersAreWhereACornerDetectorFindsThem)
{
    struct TCase {
        TSurfaceKind kind;
        double width, height;
        size_t min_corners;
    };
    for (const TCase& c :
         {TCase{TSurfaceKind::Wall, 8.0, 2.5, 30}, TCase{TSurfaceKind::Cabinet, 1.8, 1.9, 20},
          TCase{TSurfaceKind::Shelf, 1.8, 1.8, 40}, TCase{TSurfaceKind::Desk, 1.6, 0.75, 10}}) {
        for (uint32_t seed : {1u, 2u, 3u}) {
            const TPaintedTexture t = paint(c.kind, c.width, c.height, seed);
            EXPECT_EQ(t.pixels_per_metre, 200);
            EXPECT_EQ(t.image.getWidth(), static_cast<size_t>(c.width * 200));
            EXPECT_GE(t.corners.size(), c.min_corners) << "kind " << static_cast<int>(c.kind);
            const double found = fractionFoundByADetector(t);
            std::cout << "kind " << static_cast<int>(c.kind) << " seed " << seed << ": "
                      << t.corners.size() << " corners, " << 100 * found << " % found\n";
            EXPECT_GE(found, 0.9) << "kind " << static_cast<int>(c.kind) << " seed " << seed;
            for (const Eigen::Vector2d& p : t.corners) {
                EXPECT_GE(p.x(), 0.04);
                EXPECT_LE(p.x(), c.width - 0.04);
                EXPECT_GE(p.y(), 0.04);
                EXPECT_LE(p.y(), c.height - 0.04);
            }
        }
    }
}

TEST(TexturePainter, KeptCornersAreSeparatedAndStrong)
{
    const TexturePainter painter = shippedPainter();
    mrpt::random::CRandomGenerator rng(9);
    const TPaintedTexture t = painter.paint({TSurfaceKind::Shelf, 1.8, 1.8, {}, {}}, rng);
    for (size_t i = 0; i < t.corners.size(); i++)
        for (size_t j = i + 1; j < t.corners.size(); j++)
            EXPECT_GE((t.corners[i] - t.corners[j]).norm(), painter.min_corner_separation);
    // A stricter contrast threshold keeps a subset.
    TexturePainter strict = painter;
    strict.min_corner_contrast = 120;
    mrpt::random::CRandomGenerator rng2(9);
    EXPECT_LT(strict.paint({TSurfaceKind::Shelf, 1.8, 1.8, {}, {}}, rng2).corners.size(),
              t.corners.size());
}

TEST(TexturePainter, PlainSurfacesHaveNoCornersAndLowContrast)
{
    for (TSurfaceKind kind : {TSurfaceKind::Panel, TSurfaceKind::Floor, TSurfaceKind::Ceiling}) {
        const TPaintedTexture t = paint(kind, 3.0, 2.0, 4);
        EXPECT_TRUE(t.corners.empty());
        cv::Scalar mean, stddev;
        cv::meanStdDev(t.image.asCvMatRef(), mean, stddev);
        EXPECT_GT(stddev[0], 1.0);
        EXPECT_LT(stddev[0], 15.0);
    }
    EXPECT_EQ(paint(TSurfaceKind::Floor, 3.0, 2.0, 4).pixels_per_metre, 50);
}

TEST(TexturePainter, SameGeneratorStateGivesTheSameTexture)
{
    const TPaintedTexture a = paint(TSurfaceKind::Wall, 5.0, 2.5, 11);
    const TPaintedTexture b = paint(TSurfaceKind::Wall, 5.0, 2.5, 11);
    const TPaintedTexture c = paint(TSurfaceKind::Wall, 5.0, 2.5, 12);
    EXPECT_EQ(cv::countNonZero(a.image.asCvMatRef() != b.image.asCvMatRef()), 0);
    EXPECT_EQ(a.corners, b.corners);
    EXPECT_GT(cv::countNonZero(a.image.asCvMatRef() != c.image.asCvMatRef()), 0);
}

TEST(TexturePainter, DoorsArePaintedAndHiddenSpansStayFreeOfItems)
{
    constexpr double kHeight = 2.5, kDoorHeight = 2.05;
    const TWallSpan door{2.0, 2.9, kDoorHeight}, hidden{4.0, 5.5, 1.5};
    for (uint32_t seed = 1; seed <= 5; seed++) {
        const TPaintedTexture t = paint(TSurfaceKind::Wall, 7.0, kHeight, seed, {door}, {hidden});
        // The outer top corners of the 6 cm door frame are landmarks.
        for (double s : {door.s0 - 0.06, door.s1 + 0.06}) {
            const Eigen::Vector2d frame(s, kHeight - kDoorHeight - 0.06);
            EXPECT_TRUE(std::any_of(t.corners.begin(), t.corners.end(),
                                    [&](const auto& c) { return (c - frame).norm() < 0.01; }))
                << "seed " << seed;
        }
        // Behind the furniture (up to 1.5 m) nothing is painted: no corner below 1.5 m there.
        for (const Eigen::Vector2d& c : t.corners) {
            if (c.x() > hidden.s0 && c.x() < hidden.s1) {
                EXPECT_LE(c.y(), kHeight - hidden.top) << "seed " << seed;
            }
        }
    }
}

TEST(TexturePainter, BadValuesNameTheirKey)
{
    mrpt::config::CConfigFileMemory cfg;
    cfg.write("Textures", "corner_window", 0.001);
    TexturePainter p;
    try {
        p.loadFromConfigFile(cfg, "Textures");
        FAIL() << "no exception";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("[Textures] corner_window"), std::string::npos)
            << e.what();
    }
}
