#include <gtest/gtest.h>
#include <mrpt/img/CImage.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/IntegralImage.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

using mrpt::img::CImage;
using mrpt_vslam::core::IntegralImage;

namespace {

CImage randomImage(int w, int h, unsigned seed)
{
    mrpt::random::CRandomGenerator rng(seed);
    CImage img(w, h, mrpt::img::CH_GRAY);
    for (int r = 0; r < h; r++) {
        for (int c = 0; c < w; c++) img.at<uint8_t>(c, r) = uint8_t(rng.drawUniform32bit() % 256);
    }
    return img;
}

/// ∫ over [−½, x) × [−½, y) of the piecewise-constant image, pixel by pixel overlap.
double bruteIntegral(const CImage& img, double x, double y)
{
    double sum = 0;
    for (int r = 0; r < int(img.getHeight()); r++) {
        const double oy = std::clamp(y - (r - 0.5), 0.0, 1.0);
        for (int c = 0; c < int(img.getWidth()); c++) {
            const double ox = std::clamp(x - (c - 0.5), 0.0, 1.0);
            sum += ox * oy * img.at<uint8_t>(c, r);
        }
    }
    return sum;
}

}  // namespace

TEST(IntegralImage, BoxSumsEqualBruteForce)
{
    const CImage img = randomImage(37, 23, 1);
    const IntegralImage ii(img);
    EXPECT_EQ(ii.width(), 37);
    EXPECT_EQ(ii.height(), 23);
    mrpt::random::CRandomGenerator rng(2);
    for (int k = 0; k < 200; k++) {
        int c0 = int(rng.drawUniform32bit() % 38), c1 = int(rng.drawUniform32bit() % 38);
        int r0 = int(rng.drawUniform32bit() % 24), r1 = int(rng.drawUniform32bit() % 24);
        if (c0 > c1) std::swap(c0, c1);
        if (r0 > r1) std::swap(r0, r1);
        int64_t brute = 0;
        for (int r = r0; r < r1; r++) {
            for (int c = c0; c < c1; c++) brute += img.at<uint8_t>(c, r);
        }
        EXPECT_EQ(ii.boxSum(c0, r0, c1, r1), brute) << c0 << " " << r0 << " " << c1 << " " << r1;
    }
    // Whole image of a 255-valued 4096 × 4096 image overflows 32 bits but not the table.
    CImage big(4096, 4096, mrpt::img::CH_GRAY);
    for (int r = 0; r < 4096; r++) std::fill_n(big.ptrLine<uint8_t>(r), 4096, uint8_t(255));
    EXPECT_EQ(IntegralImage(big).boxSum(0, 0, 4096, 4096), int64_t(255) * 4096 * 4096);
}

TEST(IntegralImage, SubPixelIntegralIsExact)
{
    const CImage img = randomImage(11, 9, 3);
    const IntegralImage ii(img);
    // Pixel boundaries: the table entries themselves.
    EXPECT_DOUBLE_EQ(ii.integralAt(3.5, 4.5), double(ii.boxSum(0, 0, 4, 5)));
    EXPECT_DOUBLE_EQ(ii.integralAt(-0.5, 4.5), 0.0);
    EXPECT_DOUBLE_EQ(ii.integralAt(10.5, 8.5), double(ii.boxSum(0, 0, 11, 9)));
    mrpt::random::CRandomGenerator rng(4);
    for (int k = 0; k < 300; k++) {
        const double x = rng.drawUniform(-0.5, 10.5), y = rng.drawUniform(-0.5, 8.5);
        EXPECT_NEAR(ii.integralAt(x, y), bruteIntegral(img, x, y), 1e-9) << x << ", " << y;
    }
}

TEST(IntegralImage, RejectsEmptyAndDeepImages)
{
    EXPECT_THROW(IntegralImage{CImage()}, std::invalid_argument);
    CImage deep;
    deep.resize(8, 8, mrpt::img::CH_GRAY, mrpt::img::PixelDepth::D16U);
    EXPECT_THROW(IntegralImage{deep}, std::invalid_argument);
}
