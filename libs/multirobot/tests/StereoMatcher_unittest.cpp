#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/img/CImage.h>
#include <mrpt_vslam/multirobot/StereoMatcher.h>

#include <opencv2/imgproc.hpp>

#include "StereoTestScene.h"

using mrpt_vslam::multirobot::StereoMatcher;

namespace {

mrpt::img::CImage toImage(const cv::Mat& m) { return mrpt::img::CImage(m, mrpt::img::DEEP_COPY); }

/// `img` moved left by `shift` px: out(x, y) = img(x + shift, y) (bilinear).
cv::Mat shifted(const cv::Mat& img, double shift)
{
    const cv::Mat M = (cv::Mat_<double>(2, 3) << 1, 0, shift, 0, 1, 0);
    cv::Mat out;
    cv::warpAffine(img, out, M, img.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                   cv::BORDER_REFLECT);
    return out;
}

std::vector<cv::Point> corners(const cv::Mat& img)
{
    std::vector<cv::Point2f> c;
    cv::goodFeaturesToTrack(img, c, 200, 0.01, 8, cv::noArray(), 5, true, 0.04);
    std::vector<cv::Point> out;
    for (const auto& p : c) out.emplace_back(cvRound(p.x), cvRound(p.y));
    return out;
}

}  // namespace

TEST(StereoMatcher, FindsTheSubPixelDisparityOfAShiftedTexture)
{
    const cv::Mat left = mrpt_vslam::multirobot::test::makeTexture(400, 200, 3);
    for (const double d_true : {17.3, 24.0, 40.75}) {
        const cv::Mat right = shifted(left, d_true);
        const StereoMatcher matcher(toImage(left), toImage(right), {});
        size_t tried = 0, matched = 0;
        double max_error = 0, sum2 = 0;
        for (const cv::Point& p : corners(left)) {
            if (p.x < 60) continue;  // the right patch must stay inside the image
            tried++;
            const auto m = matcher.match(p.y, p.x);
            if (!m) continue;
            matched++;
            max_error = std::max(max_error, std::abs(m->disparity - d_true));
            sum2 += (m->disparity - d_true) * (m->disparity - d_true);
            EXPECT_GT(m->ncc, 0.9);
        }
        ASSERT_GT(tried, 50u);
        EXPECT_GE(matched, 0.9 * tried) << "d = " << d_true;
        // measured: RMS 0.030 / 0.037 / 0.037 px, max 0.14 / 0.17 / 0.21 px (parabola-fit bias)
        EXPECT_LT(std::sqrt(sum2 / matched), 0.06) << "d = " << d_true;
        EXPECT_LT(max_error, 0.25) << "d = " << d_true;
    }
}

// A rectification that moves the right image's principal point right of the left one's (a
// column offset o < 0) puts far points at column differences below 1 px, even below 0: with the
// offset the search moves with it and finds them; without it they lie outside the range.
// Measured: 99 of 99 corners found at both p; without the offset, 11 (wrong) at p = -2.7.
TEST(StereoMatcher, AColumnOffsetMovesTheSearchedRange)
{
    const cv::Mat left = mrpt_vslam::multirobot::test::makeTexture(400, 200, 3);
    for (const double p_true : {-2.7, 5.5}) {
        const cv::Mat right = shifted(left, p_true);
        const StereoMatcher matcher(toImage(left), toImage(right), {});
        size_t tried = 0, matched = 0, matched_without = 0;
        double max_error = 0;
        for (const cv::Point& p : corners(left)) {
            if (p.x < 60 || p.x > 340) continue;
            tried++;
            if (matcher.match(p.y, p.x)) matched_without++;
            const auto m = matcher.match(p.y, p.x, -10);
            if (!m) continue;
            matched++;
            max_error = std::max(max_error, std::abs(m->disparity - p_true));
        }
        ASSERT_GT(tried, 50u);
        EXPECT_GE(matched, 0.9 * tried) << "p = " << p_true;
        EXPECT_LT(max_error, 0.25) << "p = " << p_true;
        if (p_true < 1) {  // without the offset only a few wrong matches remain
            EXPECT_LT(matched_without, matched / 4) << "p = " << p_true;
        }
    }
}

TEST(StereoMatcher, IgnoresGainAndOffsetOfTheRightImage)
{
    const cv::Mat left = mrpt_vslam::multirobot::test::makeTexture(400, 200, 5);
    const cv::Mat right = shifted(left, 21.4);
    cv::Mat darker;
    right.convertTo(darker, CV_8U, 0.6, 40);
    const StereoMatcher same(toImage(left), toImage(right), {});
    const StereoMatcher changed(toImage(left), toImage(darker), {});
    size_t both = 0, only_same = 0;
    for (const cv::Point& p : corners(left)) {
        const auto a = same.match(p.y, p.x), b = changed.match(p.y, p.x);
        if (a && b) {
            both++;
            EXPECT_NEAR(a->disparity, b->disparity, 0.05);
        } else if (a) {
            only_same++;
        }
    }
    ASSERT_GT(both, 50u);
    EXPECT_LE(only_same, both / 20);
}

TEST(StereoMatcher, RejectsRepetitiveFlatAndOutOfRangePatches)
{
    // Vertical stripes of period 8 px: equal peaks every 8 px fail the uniqueness test.
    cv::Mat stripes(100, 300, CV_8UC1);
    for (int c = 0; c < stripes.cols; c++) stripes.col(c).setTo(c % 8 < 4 ? 40 : 200);
    cv::GaussianBlur(stripes, stripes, cv::Size(0, 0), 1.0);
    const StereoMatcher periodic(toImage(stripes), toImage(shifted(stripes, 12)), {});
    for (int c = 100; c < 290; c += 7) EXPECT_FALSE(periodic.match(50, c)) << "column " << c;

    const cv::Mat flat(100, 300, CV_8UC1, cv::Scalar(90));
    const StereoMatcher uniform(toImage(flat), toImage(flat), {});
    EXPECT_FALSE(uniform.match(50, 200));

    // True disparity 40 px beyond max_disparity = 30: the true peak is outside the search, so
    // whatever is found is wrong; min_ncc and uniqueness must turn almost all of it down.
    const cv::Mat left = mrpt_vslam::multirobot::test::makeTexture(400, 200, 9);
    StereoMatcher::TOptions opts;
    opts.max_disparity = 30;
    const StereoMatcher short_range(toImage(left), toImage(shifted(left, 40)), opts);
    size_t accepted = 0, tried = 0;
    for (const cv::Point& p : corners(left)) {
        if (p.x < 45) continue;  // the true right patch must be in the image
        tried++;
        accepted += short_range.match(p.y, p.x).has_value();
    }
    ASSERT_GT(tried, 100u);
    EXPECT_LE(accepted, tried / 20);  // measured: 5 of 132

    // Patches that leave the image
    const StereoMatcher m(toImage(left), toImage(shifted(left, 20)), {});
    EXPECT_FALSE(m.match(2, 200));
    EXPECT_FALSE(m.match(100, 398));
    EXPECT_FALSE(m.match(100, 10));  // no room for the disparities
}

TEST(StereoMatcher, LeftRightCheckRejectsAMatchThatPointsBackElsewhere)
{
    // Independent random textures left and right, plus one 15 × 15 block P: the right image
    // has P at column 80; the left image has a noisy copy of P at column 100 and P itself at
    // column 130. From left 100 the only good match is right 80 (d = 20); from right 80 the
    // best left patch is the exact copy at 130 (d = 50), so the left-right check fails.
    cv::Mat left = mrpt_vslam::multirobot::test::makeTexture(300, 100, 21);
    cv::Mat right = mrpt_vslam::multirobot::test::makeTexture(300, 100, 22);
    const cv::Mat block =
        mrpt_vslam::multirobot::test::makeTexture(300, 100, 24)(cv::Rect(140, 40, 15, 15)).clone();
    cv::Mat noise(15, 15, CV_8UC1), noisy;
    cv::RNG(5).fill(noise, cv::RNG::UNIFORM, 0, 25);
    cv::add(block, noise, noisy);
    block.copyTo(right(cv::Rect(80 - 7, 50 - 7, 15, 15)));
    noisy.copyTo(left(cv::Rect(100 - 7, 50 - 7, 15, 15)));
    block.copyTo(left(cv::Rect(130 - 7, 50 - 7, 15, 15)));

    StereoMatcher::TOptions opts;
    opts.max_disparity = 64;
    opts.left_right_check = false;
    const auto without = StereoMatcher(toImage(left), toImage(right), opts).match(50, 100);
    ASSERT_TRUE(without);
    EXPECT_NEAR(without->disparity, 20, 0.5);
    opts.left_right_check = true;
    EXPECT_FALSE(StereoMatcher(toImage(left), toImage(right), opts).match(50, 100));
}

TEST(StereoMatcher, RejectsBadImagesAndOptions)
{
    const cv::Mat a(100, 200, CV_8UC1, cv::Scalar(0)), b(100, 201, CV_8UC1, cv::Scalar(0));
    EXPECT_THROW(StereoMatcher(toImage(a), toImage(b), {}), std::invalid_argument);
    EXPECT_THROW(StereoMatcher(mrpt::img::CImage(), toImage(a), {}), std::invalid_argument);
    const cv::Mat colour(100, 200, CV_8UC3, cv::Scalar(0, 0, 0));
    EXPECT_THROW(StereoMatcher(toImage(colour), toImage(a), {}), std::invalid_argument);

    const auto loadError = [](const std::string& text) -> std::string {
        mrpt::config::CConfigFileMemory cfg("[StereoFrontEnd]\n" + text + "\n");
        StereoMatcher::TOptions o;
        try {
            o.loadFromConfigFile(cfg, "StereoFrontEnd");
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(loadError("min_disparity = 0"), "[StereoFrontEnd] min_disparity: must be >= 1");
    EXPECT_EQ(loadError("min_disparity = 10\nmax_disparity = 11"),
              "[StereoFrontEnd] max_disparity: must be >= min_disparity + 2 (a peak needs two "
              "neighbours)");
    EXPECT_EQ(loadError("ncc_window = 8"),
              "[StereoFrontEnd] ncc_window: must be odd, from 3 to 51");
    EXPECT_EQ(loadError("min_ncc = 1.5"), "[StereoFrontEnd] min_ncc: must be in (-1, 1]");
    EXPECT_EQ(loadError("uniqueness_ratio = 0"),
              "[StereoFrontEnd] uniqueness_ratio: must be in (0, 1]");
    EXPECT_EQ(loadError("min_disparity = 4\nmax_disparity = 90\nncc_window = 7"), "");
}
