#include <gtest/gtest.h>
#include <mrpt/img/CImage.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/core/USurfDescriptor.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>

using mrpt::img::CImage;
using mrpt_vslam::core::USurfDescriptor;
using TDescriptor = USurfDescriptor::TDescriptor;

namespace {

/// Grayscale float canvas; converted to an 8-bit CImage with rounding and saturation.
struct TCanvas {
    int width;
    int height;
    std::vector<double> px;

    TCanvas(int w, int h, double value) : width(w), height(h), px(size_t(w) * h, value) {}
    double& at(int col, int row) { return px[size_t(row) * width + col]; }
    double at(int col, int row) const { return px[size_t(row) * width + col]; }

    /// Window of size w × h starting at (col0, row0).
    TCanvas crop(int col0, int row0, int w, int h) const
    {
        TCanvas out(w, h, 0);
        for (int r = 0; r < h; r++) {
            for (int c = 0; c < w; c++) out.at(c, r) = at(col0 + c, row0 + r);
        }
        return out;
    }

    /// Pixel-wise a·I + b.
    TCanvas affine(double a, double b) const
    {
        TCanvas out = *this;
        for (double& v : out.px) v = a * v + b;
        return out;
    }

    CImage toImage() const
    {
        CImage img(width, height, mrpt::img::CH_GRAY);
        for (int r = 0; r < height; r++) {
            auto* line = img.ptrLine<uint8_t>(r);
            for (int c = 0; c < width; c++) {
                line[c] = static_cast<uint8_t>(std::clamp(std::lround(at(c, r)), 0L, 255L));
            }
        }
        return img;
    }
};

/// Deterministic piecewise-constant texture: random overlapping rectangles and ellipses with
/// integer gray levels in [lo, hi].
TCanvas rectangleTexture(int w, int h, unsigned seed, int lo = 0, int hi = 120)
{
    mrpt::random::CRandomGenerator rng(seed);
    TCanvas canvas(w, h, 0.5 * (lo + hi));
    const int shapes = w * h / 150;
    for (int k = 0; k < shapes; k++) {
        const double cx = rng.drawUniform(0.0, w), cy = rng.drawUniform(0.0, h);
        const double ax = rng.drawUniform(2.0, 16.0), ay = rng.drawUniform(2.0, 16.0);
        const double gray = std::round(rng.drawUniform(lo, hi));
        const bool ellipse = rng.drawUniform(0.0, 1.0) < 0.3;
        for (int r = std::max(0, int(cy - ay)); r < std::min(h, int(cy + ay) + 1); r++) {
            for (int c = std::max(0, int(cx - ax)); c < std::min(w, int(cx + ax) + 1); c++) {
                const double u = (c - cx) / ax, v = (r - cy) / ay;
                if (!ellipse || u * u + v * v <= 1) canvas.at(c, r) = gray;
            }
        }
    }
    return canvas;
}

/// Smooth texture: 60 + Σ Gaussian blobs, rendered at continuous coordinates shifted by (dx, dy).
TCanvas blobTexture(int w, int h, double shift_x, double shift_y)
{
    mrpt::random::CRandomGenerator rng(7);
    TCanvas canvas(w, h, 90.0);
    for (int k = 0; k < w * h / 200; k++) {
        const double bx = rng.drawUniform(0.0, w), by = rng.drawUniform(0.0, h);
        const double sigma = rng.drawUniform(2.0, 6.0), amp = rng.drawUniform(-40.0, 40.0);
        for (int r = 0; r < h; r++) {
            for (int c = 0; c < w; c++) {
                const double u = c - shift_x - bx, v = r - shift_y - by;
                const double e = (u * u + v * v) / (2 * sigma * sigma);
                if (e < 20) canvas.at(c, r) += amp * std::exp(-e);
            }
        }
    }
    return canvas;
}

/** Harris & Stephens (1988) corners: R = det M − 0.04 (tr M)², M the 5×5 box sum of the
 *  central-difference gradient products; local maxima above 1 % of the best, strongest first,
 *  at least `min_distance` px apart and `margin` px from the border. */
std::vector<std::pair<int, int>> harrisCorners(const TCanvas& img, int min_distance, int margin)
{
    const int w = img.width, h = img.height;
    std::vector<double> response(size_t(w) * h, 0.0);
    double best = 0;
    for (int r = 3; r < h - 3; r++) {
        for (int c = 3; c < w - 3; c++) {
            double sxx = 0, syy = 0, sxy = 0;
            for (int j = -2; j <= 2; j++) {
                for (int i = -2; i <= 2; i++) {
                    const double gx = 0.5 * (img.at(c + i + 1, r + j) - img.at(c + i - 1, r + j));
                    const double gy = 0.5 * (img.at(c + i, r + j + 1) - img.at(c + i, r + j - 1));
                    sxx += gx * gx;
                    syy += gy * gy;
                    sxy += gx * gy;
                }
            }
            const double rv = sxx * syy - sxy * sxy - 0.04 * (sxx + syy) * (sxx + syy);
            response[size_t(r) * w + c] = rv;
            best = std::max(best, rv);
        }
    }
    std::vector<std::pair<double, std::pair<int, int>>> peaks;
    for (int r = margin; r < h - margin; r++) {
        for (int c = margin; c < w - margin; c++) {
            const double rv = response[size_t(r) * w + c];
            if (rv < 0.01 * best) continue;
            bool is_max = true;
            for (int j = -1; j <= 1 && is_max; j++) {
                for (int i = -1; i <= 1; i++) {
                    if ((i || j) && response[size_t(r + j) * w + c + i] > rv) is_max = false;
                }
            }
            if (is_max) peaks.push_back({rv, {c, r}});
        }
    }
    std::sort(peaks.begin(), peaks.end(), std::greater<>());
    std::vector<std::pair<int, int>> corners;
    for (const auto& peak : peaks) {
        const int c = peak.second.first, r = peak.second.second;
        const bool far = std::all_of(corners.begin(), corners.end(), [&](const auto& q) {
            return std::hypot(q.first - c, q.second - r) >= min_distance;
        });
        if (far) corners.push_back({c, r});
    }
    return corners;
}

double norm(const TDescriptor& d)
{
    double s = 0;
    for (float v : d) s += double(v) * v;
    return std::sqrt(s);
}

}  // namespace

TEST(USurfDescriptor, HaarResponseOfVerticalStepEdge)
{
    // Columns < 32 at 50, columns ≥ 32 at 170: the edge lies at x = 31.5.
    TCanvas canvas(64, 64, 50.0);
    for (int r = 0; r < 64; r++) {
        for (int c = 32; c < 64; c++) canvas.at(c, r) = 170.0;
    }
    const USurfDescriptor usurf(canvas.toImage());
    for (const double s : {1.0, 1.5, 2.0, 3.3}) {
        // Edge through the box centre: dx = step height, dy = 0.
        EXPECT_NEAR(usurf.haarX(31.5, 20.3, s), 120.0, 1e-9) << "s=" << s;
        EXPECT_NEAR(usurf.haarY(31.5, 20.3, s), 0.0, 1e-9) << "s=" << s;
        // Box centred one pixel left of the edge: the right half [30.5, 30.5 + s) holds s − 1
        // bright columns.
        EXPECT_NEAR(usurf.haarX(30.5, 20.3, s), 120.0 * (s - 1) / s, 1e-9) << "s=" << s;
        // Sub-pixel: centred 0.25 px right of the edge, the left half holds 0.25 px of bright.
        EXPECT_NEAR(usurf.haarX(31.75, 20.3, s), 120.0 * (s - 0.25) / s, 1e-9) << "s=" << s;
        // Box entirely on one side.
        EXPECT_NEAR(usurf.haarX(10.0, 20.3, s), 0.0, 1e-9) << "s=" << s;
    }
    // The descriptor of a keypoint on the edge has no dy part and Σdx = Σ|dx| ≥ 0.
    const auto d = usurf.compute(31.5, 31.5, 2.0);
    ASSERT_TRUE(d.has_value());
    double dx_total = 0;
    for (size_t k = 0; k < USurfDescriptor::kSize; k += 4) {
        EXPECT_NEAR((*d)[k + 1], 0.0f, 1e-6);
        EXPECT_NEAR((*d)[k + 3], 0.0f, 1e-6);
        EXPECT_NEAR((*d)[k], (*d)[k + 2], 1e-6);
        EXPECT_GE((*d)[k], -1e-6f);
        dx_total += (*d)[k];
    }
    EXPECT_GT(dx_total, 0.0);
    // Sample columns 9 and 10 (centres 30.5 and 32.5) straddle the edge with dx = 60 each
    // (closed form above): only the two middle sub-region columns (c = 1, 2) respond.
    for (int r = 0; r < 4; r++) {
        EXPECT_NEAR((*d)[4 * (4 * r + 0)], 0.0f, 1e-6);
        EXPECT_NEAR((*d)[4 * (4 * r + 3)], 0.0f, 1e-6);
    }
    // Equal column weights, so sub-region row r holds 60·w₉·Σ_{i in row r} wᵢ; normalised.
    double row_weight[4] = {0, 0, 0, 0}, total = 0;
    for (int i = 0; i < 20; i++) {
        const double u = i + 0.5 - 10;
        row_weight[i / 5] += std::exp(-u * u / (2 * 3.3 * 3.3));
    }
    for (double w : row_weight) total += 2 * 2 * w * w;  // 2 columns × (Σdx, Σ|dx|)
    for (int r = 0; r < 4; r++) {
        const double expected = row_weight[r] / std::sqrt(total);
        EXPECT_NEAR((*d)[4 * (4 * r + 1)], expected, 1e-6);
        EXPECT_NEAR((*d)[4 * (4 * r + 2)], expected, 1e-6);
    }
}

TEST(USurfDescriptor, HaarResponseOfHorizontalStepEdge)
{
    // Rows ≥ 20 are brighter by 30: dy = 30 across the edge, dx = 0.
    TCanvas canvas(48, 48, 100.0);
    for (int r = 20; r < 48; r++) {
        for (int c = 0; c < 48; c++) canvas.at(c, r) = 130.0;
    }
    const USurfDescriptor usurf(canvas.toImage());
    EXPECT_NEAR(usurf.haarY(24.0, 19.5, 2.0), 30.0, 1e-9);
    EXPECT_NEAR(usurf.haarX(24.0, 19.5, 2.0), 0.0, 1e-9);
}

TEST(USurfDescriptor, UnitLength)
{
    const USurfDescriptor usurf(rectangleTexture(200, 160, 1).toImage());
    mrpt::random::CRandomGenerator rng(11);
    int computed = 0;
    for (int k = 0; k < 100; k++) {
        const double s = rng.drawUniform(1.2, 4.0);
        const auto d = usurf.compute(rng.drawUniform(45.0, 155.0), rng.drawUniform(45.0, 115.0), s);
        ASSERT_TRUE(d.has_value());
        EXPECT_NEAR(norm(*d), 1.0, 1e-6);
        computed++;
    }
    EXPECT_EQ(computed, 100);
}

TEST(USurfDescriptor, InvariantToBrightnessScaleAndOffset)
{
    // Gray levels in [0, 120]: 2·I + 7 stays in [7, 247], no saturation and no rounding.
    const TCanvas base = rectangleTexture(160, 160, 2);
    const USurfDescriptor a(base.toImage());
    const USurfDescriptor b(base.affine(2.0, 7.0).toImage());
    const USurfDescriptor dark(base.affine(0.5, 3.0).toImage());  // rounded: quantisation noise
    mrpt::random::CRandomGenerator rng(12);
    double worst_exact = 0, worst_rounded = 0;
    for (int k = 0; k < 50; k++) {
        const double x = rng.drawUniform(40.0, 120.0), y = rng.drawUniform(40.0, 120.0);
        const double s = rng.drawUniform(1.2, 3.5);
        const auto da = a.compute(x, y, s), db = b.compute(x, y, s), dd = dark.compute(x, y, s);
        ASSERT_TRUE(da && db && dd);
        worst_exact = std::max(worst_exact, USurfDescriptor::distance(*da, *db));
        worst_rounded = std::max(worst_rounded, USurfDescriptor::distance(*da, *dd));
    }
    EXPECT_LT(worst_exact, 1e-3);
    // Halving the contrast rounds half of the levels by ½: measured 0.017 worst case.
    EXPECT_LT(worst_rounded, 0.03);
}

TEST(USurfDescriptor, SameDescriptorWhenKeypointMovesWithTexture)
{
    // Integer translation: crops of one canvas at different offsets.
    const TCanvas canvas = rectangleTexture(220, 200, 3);
    const USurfDescriptor a(canvas.crop(0, 0, 180, 160).toImage());
    const USurfDescriptor b(canvas.crop(9, 5, 180, 160).toImage());
    const auto da = a.compute(90.0, 80.0, 2.0), db = b.compute(81.0, 75.0, 2.0);
    ASSERT_TRUE(da && db);
    EXPECT_LT(USurfDescriptor::distance(*da, *db), 1e-5);

    // Sub-pixel translation of a smooth texture rendered at continuous coordinates.
    const USurfDescriptor c(blobTexture(160, 160, 0.0, 0.0).toImage());
    const USurfDescriptor d(blobTexture(160, 160, 0.3, 0.6).toImage());
    double worst = 0;
    for (const double x : {60.0, 80.0, 100.0}) {
        for (const double y : {60.0, 80.0, 100.0}) {
            const auto dc = c.compute(x, y, 2.0), dd = d.compute(x + 0.3, y + 0.6, 2.0);
            ASSERT_TRUE(dc && dd);
            worst = std::max(worst, USurfDescriptor::distance(*dc, *dd));
        }
    }
    // Measured 0.024 (quantisation to 8 bits of the shifted rendering).
    EXPECT_LT(worst, 0.05);
}

TEST(USurfDescriptor, MatchesHarrisCornersInShiftedNoisyCopy)
{
    // Image b shows the same scene shifted by (−13, −6) px, with N(0, 8²) noise per pixel
    // (gray levels 20..200). Candidates are the descriptors at the true positions in b.
    const TCanvas canvas = rectangleTexture(360, 280, 4, 20, 200);
    const int shift_x = 13, shift_y = 6;
    const TCanvas ca = canvas.crop(0, 0, 320, 240);
    TCanvas cb = canvas.crop(shift_x, shift_y, 320, 240);
    mrpt::random::CRandomGenerator rng(5);
    for (double& v : cb.px) v += rng.drawGaussian1D(0.0, 8.0);
    const USurfDescriptor a(ca.toImage()), b(cb.toImage());

    const double s = 2.0;
    // Keep corners whose window fits in both images.
    const auto corners = harrisCorners(ca, 6, 22 + std::max(shift_x, shift_y));
    std::vector<TDescriptor> in_a, in_b;
    for (const auto& [c, r] : corners) {
        const auto da = a.compute(c, r, s);
        const auto db = b.compute(c - shift_x, r - shift_y, s);
        ASSERT_TRUE(da && db) << c << "," << r;
        in_a.push_back(*da);
        in_b.push_back(*db);
    }
    ASSERT_GE(in_a.size(), 100u);
    size_t correct = 0, wrong = 0;
    for (size_t i = 0; i < in_a.size(); i++) {
        const auto m = USurfDescriptor::bestMatch(in_a[i], in_b, 0.8);
        if (m && m->index == i) correct++;
        if (m && m->index != i) wrong++;
    }
    EXPECT_GE(double(correct), 0.9 * in_a.size()) << correct << " of " << in_a.size();
    EXPECT_LE(wrong, in_a.size() / 100) << wrong << " wrong matches";
}

TEST(USurfDescriptor, NoDescriptorNearTheBorderOrOnFlatPatches)
{
    const USurfDescriptor usurf(rectangleTexture(100, 80, 6).toImage());
    // s = 2: outermost box edges at ±10.5s = ±21 px must stay in [−½, 100 − ½] (rows: 80 − ½),
    // so 20.5 ≤ x ≤ 78.5 and 20.5 ≤ y ≤ 58.5.
    EXPECT_TRUE(usurf.compute(20.5, 40.0, 2.0).has_value());
    EXPECT_FALSE(usurf.compute(20.49, 40.0, 2.0).has_value());
    EXPECT_TRUE(usurf.compute(78.5, 40.0, 2.0).has_value());
    EXPECT_FALSE(usurf.compute(78.51, 40.0, 2.0).has_value());
    EXPECT_TRUE(usurf.compute(50.0, 58.5, 2.0).has_value());
    EXPECT_FALSE(usurf.compute(50.0, 58.51, 2.0).has_value());
    EXPECT_FALSE(usurf.compute(50.0, 20.49, 2.0).has_value());
    EXPECT_FALSE(usurf.fitsInImage(50.0, 40.0, 10.0));  // 200 px window
    EXPECT_FALSE(usurf.fitsInImage(-1e300, 40.0, 2.0));

    const USurfDescriptor flat(TCanvas(100, 100, 77.0).toImage());
    EXPECT_TRUE(flat.fitsInImage(50.0, 50.0, 2.0));
    EXPECT_FALSE(flat.compute(50.0, 50.0, 2.0).has_value());

    EXPECT_THROW(usurf.compute(50.0, 40.0, 0.0), std::invalid_argument);
    EXPECT_THROW(usurf.compute(std::nan(""), 40.0, 2.0), std::invalid_argument);
    EXPECT_THROW(USurfDescriptor{CImage()}, std::invalid_argument);
}

TEST(USurfDescriptor, ColourImageGivesTheGrayscaleDescriptor)
{
    const TCanvas canvas = rectangleTexture(120, 120, 8);
    const CImage gray = canvas.toImage();
    CImage colour;
    gray.colorImage(colour);
    const auto dg = USurfDescriptor(gray).compute(60.0, 60.0, 2.0);
    const auto dc = USurfDescriptor(colour).compute(60.0, 60.0, 2.0);
    ASSERT_TRUE(dg && dc);
    EXPECT_LT(USurfDescriptor::distance(*dg, *dc), 1e-5);
}

TEST(USurfDescriptor, BestMatchAppliesTheRatioTest)
{
    TDescriptor q{}, e0{}, e1{}, near{};
    q[0] = 1;
    e0[0] = 1;
    e1[1] = 1;
    near[0] = 0.8f;
    near[1] = 0.6f;
    EXPECT_DOUBLE_EQ(USurfDescriptor::distance(e0, e1), std::sqrt(2.0));
    EXPECT_NEAR(USurfDescriptor::distance(q, near), std::sqrt(0.04 + 0.36), 1e-7);

    // Distances: e1 → √2, near → √0.4 ≈ 0.632: ratio 0.447.
    const auto m = USurfDescriptor::bestMatch(q, {e1, near}, 0.5);
    ASSERT_TRUE(m.has_value());
    EXPECT_EQ(m->index, 1u);
    EXPECT_NEAR(m->distance, std::sqrt(0.4), 1e-7);
    EXPECT_NEAR(m->second_distance, std::sqrt(2.0), 1e-7);
    EXPECT_FALSE(USurfDescriptor::bestMatch(q, {e1, near}, 0.44).has_value());
    // A single candidate is always accepted; no candidate gives no match.
    const auto single = USurfDescriptor::bestMatch(q, {e1}, 0.1);
    ASSERT_TRUE(single.has_value());
    EXPECT_TRUE(std::isinf(single->second_distance));
    EXPECT_FALSE(USurfDescriptor::bestMatch(q, {}, 0.7).has_value());
    EXPECT_THROW(USurfDescriptor::bestMatch(q, {e1}, 0.0), std::invalid_argument);
    EXPECT_THROW(USurfDescriptor::bestMatch(q, {e1}, 1.5), std::invalid_argument);
}
