#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/img/CImage.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/FastHessianDetector.h>
#include <mrpt_vslam/core/IntegralImage.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

using mrpt::img::CImage;
using mrpt_vslam::core::FastHessianDetector;
using mrpt_vslam::core::IntegralImage;
using TKeypoint = FastHessianDetector::TKeypoint;

namespace {

/// Gray levels given as a function of (col, row), rounded and saturated to 8 bits.
template <typename F>
CImage makeImage(int width, int height, F gray)
{
    CImage img(width, height, mrpt::img::CH_GRAY);
    for (int r = 0; r < height; r++) {
        auto* line = img.ptrLine<uint8_t>(r);
        for (int c = 0; c < width; c++) {
            line[c] = static_cast<uint8_t>(std::clamp(std::lround(gray(c, r)), 0L, 255L));
        }
    }
    return img;
}

struct TBlob {
    double x, y, sigma, amplitude;
};

/** Background + Σ Gaussian blobs, sampled at pixel centres with the whole pattern moved by
 *  (shift_x, shift_y) px; each blob is drawn out to 5σ. */
std::vector<double> renderBlobs(int width, int height, double background,
                                const std::vector<TBlob>& blobs, double shift_x = 0,
                                double shift_y = 0)
{
    std::vector<double> px(size_t(width) * height, background);
    for (const auto& b : blobs) {
        const double bx = b.x + shift_x, by = b.y + shift_y, reach = 5 * b.sigma;
        for (int r = std::max(0, int(by - reach)); r < std::min(height, int(by + reach) + 2); r++) {
            for (int c = std::max(0, int(bx - reach)); c < std::min(width, int(bx + reach) + 2);
                 c++) {
                const double u = c - bx, v = r - by;
                px[size_t(r) * width + c] +=
                    b.amplitude * std::exp(-(u * u + v * v) / (2 * b.sigma * b.sigma));
            }
        }
    }
    return px;
}

CImage toImage(int width, int height, const std::vector<double>& px)
{
    return makeImage(width, height, [&](int c, int r) { return px[size_t(r) * width + c]; });
}

/// Random blobs (σ in [1.5, 7] px, amplitude ±[25, 60]) over an area larger than the image.
std::vector<TBlob> randomBlobs(int width, int height, unsigned seed)
{
    mrpt::random::CRandomGenerator rng(seed);
    std::vector<TBlob> blobs;
    for (int k = 0; k < width * height / 400; k++) {
        const double amp = rng.drawUniform(25.0, 60.0) * (rng.drawUniform(0.0, 1.0) < 0.5 ? -1 : 1);
        blobs.push_back({rng.drawUniform(-20.0, width + 20.0),
                         rng.drawUniform(-20.0, height + 20.0), rng.drawUniform(1.5, 7.0), amp});
    }
    return blobs;
}

/** Share of the keypoints of `a` inside [x0, x1] × [y0, y1] that have a keypoint in `b` within
 *  `max_dist` px (after subtracting `shift`) and 10 % in scale; `errors` gets the position error
 *  of each match. */
double repeatability(const std::vector<TKeypoint>& a, const std::vector<TKeypoint>& b,
                     double shift_x, double shift_y, double x0, double y0, double x1, double y1,
                     double max_dist, std::vector<double>* errors = nullptr)
{
    size_t considered = 0, found = 0;
    for (const auto& p : a) {
        if (p.x < x0 || p.x > x1 || p.y < y0 || p.y > y1) continue;
        considered++;
        double best = max_dist;
        bool hit = false;
        for (const auto& q : b) {
            const double d = std::hypot(q.x - shift_x - p.x, q.y - shift_y - p.y);
            if (d <= best && std::abs(q.scale / p.scale - 1) < 0.1 &&
                q.laplacian_sign == p.laplacian_sign) {
                best = d;
                hit = true;
            }
        }
        if (hit) {
            found++;
            if (errors) errors->push_back(best);
        }
    }
    EXPECT_GT(considered, size_t(30));
    return considered ? double(found) / considered : 0.0;
}

}  // namespace

TEST(FastHessianDetector, FilterSizesFollowTheOctaveLayout)
{
    const std::array<std::array<int, 4>, 4> expected = {
        {{9, 15, 21, 27}, {15, 27, 39, 51}, {27, 51, 75, 99}, {51, 99, 147, 195}}};
    for (int o = 0; o < 4; o++) {
        for (int i = 0; i < 4; i++)
            EXPECT_EQ(FastHessianDetector::filterSize(o, i), expected[o][i]);
    }
    EXPECT_DOUBLE_EQ(FastHessianDetector::scaleOfFilterSize(9), 1.2);
    EXPECT_DOUBLE_EQ(FastHessianDetector::scaleOfFilterSize(27), 3.6);
}

// The 9 × 9 masks of Bay et al. Fig. 1, probed with single-pixel impulses.
TEST(FastHessianDetector, NineByNineMasksMatchTheFigure)
{
    // clang-format off
    const int dyy_mask[9][9] = {  // [row][col]
        {0, 0,  1,  1,  1,  1,  1, 0, 0},
        {0, 0,  1,  1,  1,  1,  1, 0, 0},
        {0, 0,  1,  1,  1,  1,  1, 0, 0},
        {0, 0, -2, -2, -2, -2, -2, 0, 0},
        {0, 0, -2, -2, -2, -2, -2, 0, 0},
        {0, 0, -2, -2, -2, -2, -2, 0, 0},
        {0, 0,  1,  1,  1,  1,  1, 0, 0},
        {0, 0,  1,  1,  1,  1,  1, 0, 0},
        {0, 0,  1,  1,  1,  1,  1, 0, 0}};
    const int dxy_mask[9][9] = {  // [row][col]
        {0,  0,  0,  0, 0,  0,  0,  0, 0},
        {0,  1,  1,  1, 0, -1, -1, -1, 0},
        {0,  1,  1,  1, 0, -1, -1, -1, 0},
        {0,  1,  1,  1, 0, -1, -1, -1, 0},
        {0,  0,  0,  0, 0,  0,  0,  0, 0},
        {0, -1, -1, -1, 0,  1,  1,  1, 0},
        {0, -1, -1, -1, 0,  1,  1,  1, 0},
        {0, -1, -1, -1, 0,  1,  1,  1, 0},
        {0,  0,  0,  0, 0,  0,  0,  0, 0}};
    // clang-format on
    for (int r = 0; r < 9; r++) {
        for (int c = 0; c < 9; c++) {
            // A 9 × 9 image with one pixel of 81 at (c, r): the response is the mask weight.
            const CImage img =
                makeImage(9, 9, [&](int cc, int rr) { return cc == c && rr == r ? 81.0 : 0.0; });
            const auto h = FastHessianDetector::boxHessian(IntegralImage(img), 4, 4, 9);
            EXPECT_EQ(h.dyy, dyy_mask[r][c]) << c << "," << r;
            EXPECT_EQ(h.dxx, dyy_mask[c][r]) << c << "," << r;  // the transpose
            EXPECT_EQ(h.dxy, dxy_mask[r][c]) << c << "," << r;
        }
    }
}

TEST(FastHessianDetector, BoxResponsesMatchBruteForceSums)
{
    mrpt::random::CRandomGenerator rng(11);
    const int w = 61, h = 57;
    std::vector<double> px(size_t(w) * h);
    for (double& v : px) v = std::round(rng.drawUniform(0.0, 255.0));
    const CImage img = toImage(w, h, px);
    const IntegralImage ii(img);
    int checked = 0;
    for (int size : {9, 15, 21, 27, 39, 51}) {
        const int l0 = size / 3, half = (size - 1) / 2;
        for (int row = half; row < h - half; row += 3) {
            for (int col = half; col < w - half; col += 2) {
                // Σ weight · pixel over the filter support, weights from the lobe layout.
                double dxx = 0, dyy = 0, dxy = 0;
                for (int dy = -half; dy <= half; dy++) {
                    for (int dx = -half; dx <= half; dx++) {
                        const double p = px[size_t(row + dy) * w + col + dx];
                        const auto lobe = [&](int along, int across) {
                            if (std::abs(across) > l0 - 1) return 0;
                            return std::abs(along) <= (l0 - 1) / 2 ? -2 : 1;
                        };
                        dyy += lobe(dy, dx) * p;
                        dxx += lobe(dx, dy) * p;
                        if (dx != 0 && dy != 0 && std::abs(dx) <= l0 && std::abs(dy) <= l0) {
                            dxy += ((dx > 0) == (dy > 0) ? 1 : -1) * p;
                        }
                    }
                }
                const auto box = FastHessianDetector::boxHessian(ii, col, row, size);
                const double area = double(size) * size;
                ASSERT_NEAR(box.dxx * area, dxx, 1e-6) << size << " " << col << "," << row;
                ASSERT_NEAR(box.dyy * area, dyy, 1e-6) << size << " " << col << "," << row;
                ASSERT_NEAR(box.dxy * area, dxy, 1e-6) << size << " " << col << "," << row;
                EXPECT_NEAR(box.determinant(), (dxx * dyy - 0.81 * dxy * dxy) / (area * area),
                            1e-9 * (1 + std::abs(box.determinant())));
                checked++;
            }
        }
    }
    EXPECT_GT(checked, 300);
}

TEST(FastHessianDetector, NoDetectionsOnFlatOrLinearImages)
{
    FastHessianDetector::TOptions opts;
    opts.hessian_threshold = 0;  // any positive response would be a keypoint
    const FastHessianDetector detector(opts);
    const CImage flat = makeImage(200, 160, [](int, int) { return 128.0; });
    EXPECT_TRUE(detector.detect(IntegralImage(flat)).empty());
    // Exactly linear in both directions: every second difference vanishes.
    const CImage ramp = makeImage(200, 50, [](int c, int r) { return c + r; });
    EXPECT_TRUE(detector.detect(IntegralImage(ramp)).empty());
    // A single blob is found by the same detector (the test above can fail).
    const CImage blob = toImage(200, 160, renderBlobs(200, 160, 128, {{100, 80, 3, 60}}));
    EXPECT_FALSE(detector.detect(IntegralImage(blob)).empty());
}

TEST(FastHessianDetector, FindsGaussianBlobsAtTheirCentreAndScale)
{
    const int w = 640, h = 480;
    // From the smallest scale the first octave resolves (L = 15) to octave 3.
    const std::array<double, 8> sigmas = {2.5, 3.2, 4.0, 5.0, 6.4, 8.0, 10.0, 12.5};
    std::vector<TBlob> blobs;
    for (size_t k = 0; k < sigmas.size(); k++) {
        // Sub-pixel centres; bright and dark blobs alternate.
        blobs.push_back({90.0 + 150 * (k % 4) + 0.3 * k, 130.0 + 210 * (k / 4) - 0.17 * k,
                         sigmas[k], k % 2 ? -80.0 : 80.0});
    }
    const CImage img = toImage(w, h, renderBlobs(w, h, 128, blobs));
    FastHessianDetector::TOptions opts;
    opts.hessian_threshold = 50;
    const auto kps = FastHessianDetector(opts).detect(IntegralImage(img));
    std::vector<double> ratios;
    for (const auto& b : blobs) {
        // The strongest keypoint near the blob.
        const TKeypoint* best = nullptr;
        for (const auto& kp : kps) {
            if (std::hypot(kp.x - b.x, kp.y - b.y) < 2 * b.sigma &&
                (!best || kp.response > best->response)) {
                best = &kp;
            }
        }
        ASSERT_NE(best, nullptr) << "sigma " << b.sigma;
        EXPECT_LT(std::hypot(best->x - b.x, best->y - b.y), 0.5) << "sigma " << b.sigma;
        EXPECT_EQ(best->laplacian_sign, b.amplitude > 0 ? -1 : 1) << "sigma " << b.sigma;
        ratios.push_back(best->scale / b.sigma);
    }
    // The box filters of size L are wider than a Gaussian of σ = 1.2·L/9 (a second difference
    // of lobes l0 = L/3 has σ ≈ l0/2 = 1.25·(1.2·L/9)), so a blob of σ peaks at s ≈ 0.72σ.
    for (double r : ratios) EXPECT_NEAR(r, 0.74, 0.06);
    const auto [lo, hi] = std::minmax_element(ratios.begin(), ratios.end());
    EXPECT_LT(*hi / *lo, 1.15);  // proportional to σ
    // Nothing on the flat background: every keypoint lies on a blob.
    for (const auto& kp : kps) {
        const bool on_blob = std::any_of(blobs.begin(), blobs.end(), [&](const TBlob& b) {
            return std::hypot(kp.x - b.x, kp.y - b.y) < 3 * b.sigma;
        });
        EXPECT_TRUE(on_blob) << kp.x << "," << kp.y << " s=" << kp.scale;
    }
}

TEST(FastHessianDetector, InvariantToBrightnessAndRepeatableUnderContrast)
{
    const int w = 320, h = 240;
    const auto px = renderBlobs(w, h, 120, randomBlobs(w, h, 21));
    const CImage img = toImage(w, h, px);
    FastHessianDetector::TOptions opts;
    opts.hessian_threshold = 30;
    const auto base = FastHessianDetector(opts).detect(IntegralImage(img));
    ASSERT_GT(base.size(), size_t(50));

    // An offset cancels in every box filter (weights sum to zero): identical keypoints, as long
    // as nothing saturates.
    std::vector<double> brighter = px;
    for (double& v : brighter) v = std::clamp(std::round(v), 0.0, 255.0) + 20;
    ASSERT_LE(*std::max_element(brighter.begin(), brighter.end()), 255.0);
    const auto shifted = FastHessianDetector(opts).detect(IntegralImage(toImage(w, h, brighter)));
    ASSERT_EQ(shifted.size(), base.size());
    for (size_t k = 0; k < base.size(); k++) {
        EXPECT_EQ(shifted[k].x, base[k].x);
        EXPECT_EQ(shifted[k].y, base[k].y);
        EXPECT_EQ(shifted[k].scale, base[k].scale);
        EXPECT_EQ(shifted[k].response, base[k].response);
    }

    // Contrast × 0.6 (rounded to 8 bits again): det(H) scales by 0.36, so does the threshold.
    const double a = 0.6;
    std::vector<double> lower = px;
    for (double& v : lower) v = a * std::clamp(std::round(v), 0.0, 255.0) + 40;
    auto scaled_opts = opts;
    scaled_opts.hessian_threshold = opts.hessian_threshold * a * a;
    const auto contrast =
        FastHessianDetector(scaled_opts).detect(IntegralImage(toImage(w, h, lower)));
    // Keypoints well above the threshold (rounding moves borderline ones).
    std::vector<TKeypoint> strong;
    for (const auto& kp : base) {
        if (kp.response > 2 * opts.hessian_threshold) strong.push_back(kp);
    }
    EXPECT_GT(repeatability(strong, contrast, 0, 0, 0, 0, w, h, 1.0), 0.95);
}

TEST(FastHessianDetector, RepeatableUnderTranslation)
{
    // One texture, rendered twice with the pattern moved by a whole and by a fractional shift.
    const int w = 360, h = 280;
    const auto blobs = randomBlobs(w, h, 33);
    FastHessianDetector::TOptions opts;
    opts.hessian_threshold = 30;
    const FastHessianDetector detector(opts);
    const auto base = detector.detect(IntegralImage(toImage(w, h, renderBlobs(w, h, 120, blobs))));
    // Compare away from the border, where both images see the same texture and filters.
    const double m = 60;
    for (const auto& shift : {std::array<double, 2>{8, 5}, std::array<double, 2>{3.4, -2.7}}) {
        const auto moved = detector.detect(
            IntegralImage(toImage(w, h, renderBlobs(w, h, 120, blobs, shift[0], shift[1]))));
        std::vector<double> errors;
        const double rep =
            repeatability(base, moved, shift[0], shift[1], m, m, w - m, h - m, 1.0, &errors);
        EXPECT_GT(rep, 0.9) << shift[0] << "," << shift[1];
        double sum2 = 0;
        for (double e : errors) sum2 += e * e;
        EXPECT_LT(std::sqrt(sum2 / errors.size()), 0.25) << shift[0] << "," << shift[1];
    }
}

TEST(FastHessianDetector, OptionsFromIniAndValidation)
{
    mrpt::config::CConfigFileMemory ini(
        "[SURF]\n"
        "hessian_threshold = 250\n"
        "octaves = 3\n"
        "initial_step = 2\n");
    FastHessianDetector::TOptions opts;
    opts.loadFromConfigFile(ini, "SURF");
    EXPECT_DOUBLE_EQ(opts.hessian_threshold, 250.0);
    EXPECT_EQ(opts.octaves, 3);
    EXPECT_EQ(opts.initial_step, 2);
    mrpt::config::CConfigFileMemory saved;
    opts.saveToConfigFile(saved, "S");
    std::string text;
    saved.getContent(text);
    FastHessianDetector::TOptions reread;
    reread.loadFromConfigFile(mrpt::config::CConfigFileMemory(text), "S");
    EXPECT_DOUBLE_EQ(reread.hessian_threshold, 250.0);
    EXPECT_EQ(reread.octaves, 3);
    EXPECT_EQ(reread.initial_step, 2);

    for (const char* bad : {"hessian_threshold = -1\n", "octaves = 0\n", "initial_step = 0\n"}) {
        FastHessianDetector::TOptions o;
        try {
            o.loadFromConfigFile(mrpt::config::CConfigFileMemory(std::string("[S]\n") + bad), "S");
            ADD_FAILURE() << "accepted " << bad;
        } catch (const std::invalid_argument& e) {
            const std::string key = std::string(bad).substr(0, std::string(bad).find(' '));
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    }
    FastHessianDetector::TOptions neg;
    neg.initial_step = -2;
    EXPECT_THROW(FastHessianDetector{neg}, std::invalid_argument);
}
