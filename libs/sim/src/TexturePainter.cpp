#include <mrpt_vslam/sim/ConfigReading.h>
#include <mrpt_vslam/sim/TexturePainter.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace mrpt_vslam::sim {

namespace {

using Vec2 = Eigen::Vector2d;

/** A texture being painted, in face coordinates [m] (s right, t down), with the designed
 *  corners of everything painted so far. */
class Canvas {
  public:
    Canvas(double width, double height, double ppm)
        : m_width(width),
          m_height(height),
          m_ppm(ppm),
          m_mat(static_cast<int>(std::ceil(height * ppm - 1e-9)),
                static_cast<int>(std::ceil(width * ppm - 1e-9)), CV_8UC1)
    {
    }

    double width() const { return m_width; }    ///< [m] of the face
    double height() const { return m_height; }  ///< [m] of the face
    const cv::Mat& mat() const { return m_mat; }
    double ppm() const { return m_ppm; }
    const std::vector<Vec2>& candidates() const { return m_candidates; }

    /// Base gray + smooth blotches (std `blotch`, ~0.3 m) + fine noise (std `noise`).
    void background(double base, double blotch, double noise, mrpt::random::CRandomGenerator& rng)
    {
        const int gw = static_cast<int>(std::ceil(width() / 0.3)) + 2;
        const int gh = static_cast<int>(std::ceil(height() / 0.3)) + 2;
        cv::Mat coarse(gh, gw, CV_32F);
        for (int r = 0; r < gh; r++)
            for (int c = 0; c < gw; c++)
                coarse.at<float>(r, c) =
                    static_cast<float>(base + blotch * rng.drawGaussian1D_normalized());
        cv::Mat smooth;
        cv::resize(coarse, smooth, m_mat.size(), 0, 0, cv::INTER_CUBIC);
        for (int r = 0; r < m_mat.rows; r++) {
            uint8_t* row = m_mat.ptr<uint8_t>(r);
            const float* base_row = smooth.ptr<float>(r);
            for (int c = 0; c < m_mat.cols; c++)
                row[c] = cv::saturate_cast<uint8_t>(base_row[c] +
                                                    noise * rng.drawGaussian1D_normalized());
        }
    }

    /// Fills a convex polygon (vertices [m]) with `gray`, 4 × 4 sub-samples per texel; its
    /// vertices become candidates.
    void polygon(const std::vector<Vec2>& v, double gray)
    {
        double area2 = 0;
        for (size_t i = 0; i < v.size(); i++) {
            const Vec2& a = v[i];
            const Vec2& b = v[(i + 1) % v.size()];
            area2 += a.x() * b.y() - b.x() * a.y();
        }
        const double orientation = area2 > 0 ? 1.0 : -1.0;
        std::vector<Vec2> p;  // in texels
        double x_min = 1e18, x_max = -1e18, y_min = 1e18, y_max = -1e18;
        for (const Vec2& q : v) {
            p.push_back(q * m_ppm);
            x_min = std::min(x_min, p.back().x()), x_max = std::max(x_max, p.back().x());
            y_min = std::min(y_min, p.back().y()), y_max = std::max(y_max, p.back().y());
            m_candidates.push_back(q);
        }
        const auto inside = [&](double x, double y) {
            for (size_t i = 0; i < p.size(); i++) {
                const Vec2& a = p[i];
                const Vec2& b = p[(i + 1) % p.size()];
                if (orientation * ((b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (x - a.x())) <
                    0)
                    return false;
            }
            return true;
        };
        constexpr int kSub = 4;
        const int c0 = std::max(0, static_cast<int>(std::floor(x_min)));
        const int c1 = std::min(m_mat.cols - 1, static_cast<int>(std::ceil(x_max)));
        const int r0 = std::max(0, static_cast<int>(std::floor(y_min)));
        const int r1 = std::min(m_mat.rows - 1, static_cast<int>(std::ceil(y_max)));
        for (int r = r0; r <= r1; r++) {
            uint8_t* row = m_mat.ptr<uint8_t>(r);
            for (int c = c0; c <= c1; c++) {
                int hits = 0;
                for (int i = 0; i < kSub; i++)
                    for (int j = 0; j < kSub; j++)
                        hits += inside(c + (j + 0.5) / kSub, r + (i + 0.5) / kSub);
                if (hits == 0) continue;
                const double cover = hits / double(kSub * kSub);
                row[c] = cv::saturate_cast<uint8_t>((1 - cover) * row[c] + cover * gray);
            }
        }
    }

    /** Axis-aligned rectangle [s0, s1] × [t0, t1] snapped to the texel grid (whole texels).
     *  Without `bottom_corners` only its top corners become candidates (something standing on
     *  a board meets it in T-junctions, which detectors localise poorly). */
    void rect(double s0, double t0, double s1, double t1, double gray, bool bottom_corners = true)
    {
        const auto texel = [&](double x) { return static_cast<int>(std::lround(x * m_ppm)); };
        const int c0 = texel(s0), c1 = texel(s1), r0 = texel(t0), r1 = texel(t1);
        if (c1 <= c0 || r1 <= r0) return;
        for (int c : {c0, c1}) {
            m_candidates.emplace_back(c / m_ppm, r0 / m_ppm);
            if (bottom_corners) m_candidates.emplace_back(c / m_ppm, r1 / m_ppm);
        }
        const cv::Rect roi =
            cv::Rect(c0, r0, c1 - c0, r1 - r0) & cv::Rect(0, 0, m_mat.cols, m_mat.rows);
        m_mat(roi).setTo(cv::saturate_cast<uint8_t>(gray));
    }

  private:
    double m_width, m_height, m_ppm;
    cv::Mat m_mat;
    std::vector<Vec2> m_candidates;
};

/// A gray in [lo, hi] at least `min_diff` away from each of `others`.
double contrastingGray(mrpt::random::CRandomGenerator& rng, double lo, double hi,
                       std::initializer_list<double> others, double min_diff)
{
    double g = 0;
    for (int attempt = 0; attempt < 100; attempt++) {
        g = rng.drawUniform(lo, hi);
        if (std::all_of(others.begin(), others.end(),
                        [&](double o) { return std::abs(g - o) >= min_diff; }))
            return g;
    }
    // Far end of the range from the first reference.
    const double ref = *others.begin();
    return ref - lo > hi - ref ? lo : hi;
}

/// Handle: a dark or light bar (whichever stands out more) of w × h centred at (s, t).
void handle(Canvas& cv, double s, double t, double w, double h, double panel_gray)
{
    cv.rect(s - w / 2, t - h / 2, s + w / 2, t + h / 2, panel_gray > 128 ? 25 : 235);
}

void paintPoster(Canvas& cv, double s0, double t0, double w, double h, double wall,
                 mrpt::random::CRandomGenerator& rng)
{
    const double paper = contrastingGray(rng, 20, 235, {wall}, 40);
    cv.rect(s0, t0, s0 + w, t0 + h, paper);
    const int shapes = 3 + static_cast<int>(rng.drawUniform32bit() % 5);
    constexpr double kMargin = 0.03;
    for (int k = 0; k < shapes; k++) {
        const double gray = contrastingGray(rng, 10, 245, {paper}, 50);
        if (rng.drawUniform(0.0, 1.0) < 0.6) {
            const double rw = rng.drawUniform(0.1, std::max(0.1, 0.5 * w));
            const double rh = rng.drawUniform(0.1, std::max(0.1, 0.5 * h));
            if (rw > w - 2 * kMargin || rh > h - 2 * kMargin) continue;
            const double rs = s0 + rng.drawUniform(kMargin, w - kMargin - rw);
            const double rt = t0 + rng.drawUniform(kMargin, h - kMargin - rh);
            cv.rect(rs, rt, rs + rw, rt + rh, gray);
        } else {
            // Triangle inscribed in a circle of radius r.
            const double r = rng.drawUniform(0.07, 0.2);
            if (2 * r > w - 2 * kMargin || 2 * r > h - 2 * kMargin) continue;
            const Vec2 c(s0 + rng.drawUniform(kMargin + r, w - kMargin - r),
                         t0 + rng.drawUniform(kMargin + r, h - kMargin - r));
            const double a0 = rng.drawUniform(0.0, 2 * M_PI);
            const double a1 = a0 + rng.drawUniform(M_PI / 2, 5 * M_PI / 6);
            // Arcs of 90°-150°, 90°-150° and the rest (60°-180°): interior angles 30°-90°.
            const double a2 = a1 + rng.drawUniform(M_PI / 2, 5 * M_PI / 6);
            std::vector<Vec2> tri;
            for (double a : {a0, a1, a2}) tri.push_back(c + r * Vec2(std::cos(a), std::sin(a)));
            cv.polygon(tri, gray);
        }
    }
}

/// Returns false (and paints nothing) when the region is too small for a 3 × 3 board.
bool paintCheckerboard(Canvas& cv, double s0, double t0, double w, double h,
                       mrpt::random::CRandomGenerator& rng)
{
    constexpr double kMargin = 0.04;
    const double cell = rng.drawUniform(0.08, 0.14);
    const int cols = std::min(8, static_cast<int>((w - 2 * kMargin) / cell));
    const int rows = std::min(6, static_cast<int>((h - 2 * kMargin) / cell));
    if (cols < 3 || rows < 3) return false;
    const bool strong = rng.drawUniform(0.0, 1.0) < 0.7;
    const double dark = strong ? rng.drawUniform(10, 60) : rng.drawUniform(70, 100);
    const double light = strong ? rng.drawUniform(185, 245) : rng.drawUniform(150, 180);
    const double bw = cols * cell + 2 * kMargin, bh = rows * cell + 2 * kMargin;
    const double bs = s0 + (w - bw) / 2, bt = t0 + (h - bh) / 2;
    cv.rect(bs, bt, bs + bw, bt + bh, light);
    for (int r = 0; r < rows; r++)
        for (int c = 0; c < cols; c++)
            if ((r + c) % 2 == 0)
                cv.rect(bs + kMargin + c * cell, bt + kMargin + r * cell,
                        bs + kMargin + (c + 1) * cell, bt + kMargin + (r + 1) * cell, dark);
    return true;
}

void paintDoor(Canvas& cv, const TWallSpan& door, double wall, mrpt::random::CRandomGenerator& rng)
{
    constexpr double kFrame = 0.06;
    const double floor_t = cv.height(), top_t = floor_t - door.top;
    const double frame = contrastingGray(rng, 30, 235, {wall}, 60);
    const double leaf = contrastingGray(rng, 40, 220, {frame}, 50);
    cv.rect(door.s0 - kFrame, top_t - kFrame, door.s1 + kFrame, floor_t, frame);
    cv.rect(door.s0, top_t, door.s1, floor_t, leaf);
    const double panel = leaf + (leaf > 128 ? -35 : 35);
    if (door.s1 - door.s0 > 0.5 && door.top > 1.9) {
        cv.rect(door.s0 + 0.12, top_t + 0.12, door.s1 - 0.12, top_t + 0.12 + 0.8, panel);
        cv.rect(door.s0 + 0.12, floor_t - 0.82, door.s1 - 0.12, floor_t - 0.12, panel);
    }
    handle(cv, door.s1 - 0.125, floor_t - 1.0, 0.15, 0.045, leaf);
}

void paintWall(Canvas& cv, const TFaceRequest& face, const TexturePainter& p,
               mrpt::random::CRandomGenerator& rng)
{
    const double wall = rng.drawUniform(120, 180);
    cv.background(wall, p.background_blotch_std, p.background_noise_std, rng);
    for (const TWallSpan& door : face.doors) paintDoor(cv, door, wall, rng);

    constexpr double kDoorClearance = 0.2, kMinBottom = 0.25, kMaxTop = 2.2, kEdge = 0.1;
    const double top_limit = std::min(face.height - 0.15, kMaxTop);
    double s = rng.drawUniform(0.1, p.item_gap_max);
    while (true) {
        const double w = rng.drawUniform(0.5, 1.3);
        if (s + w > face.width - kEdge) break;
        bool blocked = false;
        double bottom = kMinBottom;
        for (const TWallSpan& d : face.doors)
            if (s < d.s1 + kDoorClearance && s + w > d.s0 - kDoorClearance) {
                blocked = true;
                s = std::max(s, d.s1 + kDoorClearance);
            }
        for (const TWallSpan& k : face.keep_clear)
            if (s < k.s1 && s + w > k.s0) bottom = std::max(bottom, k.top + 0.1);
        if (blocked) continue;
        if (top_limit - bottom < 0.4) {
            s += 0.3;
            continue;
        }
        const double h = rng.drawUniform(0.4, std::min(1.1, top_limit - bottom));
        const double lift = rng.drawUniform(0.0, std::min(0.5, top_limit - bottom - h));
        const double t0 = face.height - (bottom + lift + h);
        const double kind = rng.drawUniform(0.0, 1.0);
        if (kind < 0.55 || (kind < 0.85 && !paintCheckerboard(cv, s, t0, w, h, rng)))
            paintPoster(cv, s, t0, w, h, wall, rng);
        s += w + rng.drawUniform(p.item_gap_min, p.item_gap_max);
    }
}

void paintCabinet(Canvas& cv, const TFaceRequest& face, mrpt::random::CRandomGenerator& rng)
{
    constexpr double kBorder = 0.03, kPlinth = 0.08;
    const double carcass = rng.drawUniform(60, 200);
    cv.rect(0, 0, face.width, face.height, carcass);
    cv.rect(0, face.height - kPlinth, face.width, face.height,
            carcass > 100 ? carcass - 45 : carcass + 45);
    const double inner_w = face.width - 2 * kBorder, inner_h = face.height - kPlinth - kBorder;
    const int columns = std::max(1, static_cast<int>(std::lround(inner_w / 0.5)));
    const double col_w = inner_w / columns;
    double left_gray = carcass;
    for (int c = 0; c < columns; c++) {
        const double s0 = kBorder + c * col_w;
        const bool drawers = rng.drawUniform(0.0, 1.0) < 0.5;
        const int n = drawers ? 3 + static_cast<int>(rng.drawUniform32bit() % 3)
                              : 1 + static_cast<int>(rng.drawUniform32bit() % 2);
        const double panel_h = inner_h / n;
        double above = carcass;
        for (int k = 0; k < n; k++) {
            const double t0 = kBorder + k * panel_h;
            const double gray = contrastingGray(rng, 20, 235, {above, left_gray, carcass}, 25);
            cv.rect(s0, t0, s0 + col_w, t0 + panel_h, gray);
            if (drawers)
                handle(cv, s0 + col_w / 2, t0 + std::min(0.1, panel_h / 3), 0.15, 0.045, gray);
            else
                handle(cv, s0 + (c % 2 ? 0.06 : col_w - 0.06), t0 + panel_h / 2, 0.045, 0.15, gray);
            above = gray;
        }
        left_gray = above;
    }
}

void paintShelf(Canvas& cv, const TFaceRequest& face, mrpt::random::CRandomGenerator& rng)
{
    constexpr double kSide = 0.025, kBoard = 0.025, kPlinth = 0.06, kCompartment = 0.36;
    const double carcass = rng.drawUniform(150, 210), interior = rng.drawUniform(25, 50);
    cv.rect(0, 0, face.width, face.height, carcass);
    const int compartments =
        std::max(1, static_cast<int>((face.height - kPlinth - kBoard) / kCompartment));
    const double comp_h = (face.height - kPlinth - kBoard) / compartments - kBoard;
    for (int k = 0; k < compartments; k++) {
        const double t0 = kBoard + k * (comp_h + kBoard), t1 = t0 + comp_h;
        const double s_left = kSide, s_right = face.width - kSide;
        cv.rect(s_left, t0, s_right, t1, interior);
        double s = s_left + rng.drawUniform(0.0, 0.12);
        while (true) {
            const double bw = rng.drawUniform(0.05, 0.1);
            if (s + bw > s_right) break;
            const double bh = rng.drawUniform(0.6, 0.9) * comp_h;
            cv.rect(s, t1 - bh, s + bw, t1, contrastingGray(rng, 50, 235, {interior}, 40), false);
            s += bw;
            if (rng.drawUniform(0.0, 1.0) < 0.15) s += rng.drawUniform(0.05, 0.2);
        }
    }
}

void paintDesk(Canvas& cv, const TFaceRequest& face, mrpt::random::CRandomGenerator& rng)
{
    constexpr double kTop = 0.03, kPedestal = 0.42, kSide = 0.03, kInset = 0.02;
    const double board = rng.drawUniform(140, 220), knee = rng.drawUniform(25, 50);
    cv.rect(0, 0, face.width, face.height, board);
    const bool pedestal_left = rng.drawUniform(0.0, 1.0) < 0.5;
    const double ps0 = pedestal_left ? 0 : face.width - kPedestal;
    const double ks0 = pedestal_left ? kPedestal : kSide;
    const double ks1 = pedestal_left ? face.width - kSide : face.width - kPedestal;
    cv.rect(ks0, kTop, ks1, face.height, knee);
    if (rng.drawUniform(0.0, 1.0) < 0.5)  // modesty panel
        cv.rect(ks0, kTop, ks1, kTop + 0.35, contrastingGray(rng, 60, 200, {knee, board}, 40));
    const double drawer_h = (face.height - kTop - 0.06) / 3;
    double above = board;
    for (int k = 0; k < 3; k++) {
        const double t0 = kTop + kInset / 2 + k * drawer_h;
        const double gray = contrastingGray(rng, 40, 230, {above, board}, 25);
        cv.rect(ps0 + kInset, t0, ps0 + kPedestal - kInset, t0 + drawer_h - kInset, gray);
        handle(cv, ps0 + kPedestal / 2, t0 + std::min(0.08, drawer_h / 3), 0.15, 0.045, gray);
        above = gray;
    }
}

/// Equivalent contrast √(2 λ_min / w) of the corner at texel position (x, y) (texel edges at
/// integers), or −1 when the window does not fit in the texture.
double cornerContrast(const cv::Mat& img, double x, double y, int w)
{
    const int x0 = static_cast<int>(std::lround(x)) - w, y0 = static_cast<int>(std::lround(y)) - w;
    if (x0 < 1 || y0 < 1 || x0 + 2 * w + 1 > img.cols || y0 + 2 * w + 1 > img.rows) return -1;
    double sxx = 0, syy = 0, sxy = 0;
    for (int r = y0; r < y0 + 2 * w; r++) {
        const uint8_t* up = img.ptr<uint8_t>(r - 1);
        const uint8_t* row = img.ptr<uint8_t>(r);
        const uint8_t* down = img.ptr<uint8_t>(r + 1);
        for (int c = x0; c < x0 + 2 * w; c++) {
            const double gx = 0.5 * (row[c + 1] - row[c - 1]);
            const double gy = 0.5 * (down[c] - up[c]);
            sxx += gx * gx, syy += gy * gy, sxy += gx * gy;
        }
    }
    const double mean = 0.5 * (sxx + syy);
    const double lambda_min = mean - std::sqrt(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy);
    return std::sqrt(std::max(0.0, 2 * lambda_min / w));
}

/** Whether sub-pixel corner refinement (cv::cornerSubPix: the point where the gradients of the
 *  (2w + 1)² window are orthogonal to the vectors towards it) started 1.5 texels away on either
 *  diagonal comes back to the corner at texel position (x, y) within 1 texel. Junctions of
 *  several overlapping shapes that a detector would place elsewhere fail. */
bool isLocalisable(const cv::Mat& img, double x, double y, int w)
{
    // OpenCV puts texel centres at integers; corners are on texel edges.
    const cv::Point2f corner(static_cast<float>(x - 0.5), static_cast<float>(y - 0.5));
    std::vector<cv::Point2f> starts{
        corner + cv::Point2f(1.5f, 1.5f), corner - cv::Point2f(1.5f, 1.5f),
        corner + cv::Point2f(1.5f, -1.5f), corner - cv::Point2f(1.5f, -1.5f)};
    cv::cornerSubPix(img, starts, cv::Size(w, w), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 40, 0.01));
    return std::all_of(starts.begin(), starts.end(),
                       [&](const cv::Point2f& p) { return cv::norm(p - corner) <= 1.0; });
}

}  // namespace

TPaintedTexture TexturePainter::paint(const TFaceRequest& face,
                                      mrpt::random::CRandomGenerator& rng) const
{
    const bool plain = face.kind == TSurfaceKind::Floor || face.kind == TSurfaceKind::Ceiling;
    Canvas cv(face.width, face.height, plain ? floor_pixels_per_metre : pixels_per_metre);
    switch (face.kind) {
        case TSurfaceKind::Wall:
            paintWall(cv, face, *this, rng);
            break;
        case TSurfaceKind::Cabinet:
            paintCabinet(cv, face, rng);
            break;
        case TSurfaceKind::Shelf:
            paintShelf(cv, face, rng);
            break;
        case TSurfaceKind::Desk:
            paintDesk(cv, face, rng);
            break;
        case TSurfaceKind::Panel:
            cv.background(rng.drawUniform(90, 200), background_blotch_std, background_noise_std,
                          rng);
            break;
        case TSurfaceKind::Floor:
            cv.background(95, background_blotch_std, background_noise_std, rng);
            break;
        case TSurfaceKind::Ceiling:
            cv.background(205, background_blotch_std, background_noise_std, rng);
            break;
    }

    // Designed corners: unique, detectable, well separated.
    const int w = std::max(1, static_cast<int>(std::lround(corner_window * cv.ppm())));
    std::vector<Vec2> detectable;
    for (const Vec2& c : cv.candidates()) {
        if (c.x() < corner_window || c.y() < corner_window || c.x() > face.width - corner_window ||
            c.y() > face.height - corner_window)
            continue;
        if (std::any_of(detectable.begin(), detectable.end(),
                        [&](const Vec2& d) { return (d - c).norm() < 0.5 / cv.ppm(); }))
            continue;
        if (cornerContrast(cv.mat(), c.x() * cv.ppm(), c.y() * cv.ppm(), w) >=
                min_corner_contrast &&
            isLocalisable(cv.mat(), c.x() * cv.ppm(), c.y() * cv.ppm(), std::max(1, w / 2)))
            detectable.push_back(c);
    }
    TPaintedTexture out;
    out.pixels_per_metre = cv.ppm();
    for (const Vec2& c : detectable)
        if (std::none_of(detectable.begin(), detectable.end(), [&](const Vec2& d) {
                return &d != &c && (d - c).norm() < min_corner_separation;
            }))
            out.corners.push_back(c);
    out.image = mrpt::img::CImage(cv.mat(), mrpt::img::DEEP_COPY);
    return out;
}

void TexturePainter::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                        const std::string& s)
{
    MRPT_LOAD_CONFIG_VAR(pixels_per_metre, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(floor_pixels_per_metre, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(background_noise_std, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(background_blotch_std, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(min_corner_contrast, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(corner_window, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(min_corner_separation, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(item_gap_min, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(item_gap_max, double, cfg, s);
    checkConfig(pixels_per_metre >= 20 && pixels_per_metre <= 1000, s, "pixels_per_metre",
                "in [20, 1000]");
    checkConfig(floor_pixels_per_metre >= 5 && floor_pixels_per_metre <= 1000, s,
                "floor_pixels_per_metre", "in [5, 1000]");
    checkConfig(background_noise_std >= 0, s, "background_noise_std", ">= 0");
    checkConfig(background_blotch_std >= 0, s, "background_blotch_std", ">= 0");
    checkConfig(min_corner_contrast >= 0, s, "min_corner_contrast", ">= 0");
    checkConfig(corner_window * pixels_per_metre >= 2 && corner_window <= 0.2, s, "corner_window",
                "at least 2 texels and <= 0.2 m");
    checkConfig(min_corner_separation >= 0, s, "min_corner_separation", ">= 0");
    checkConfig(item_gap_min > 0 && item_gap_min <= item_gap_max, s, "item_gap_min/max",
                "0 < min <= max");
}

}  // namespace mrpt_vslam::sim
