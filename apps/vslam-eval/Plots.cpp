#include "Plots.h"

#include <mrpt/core/bits_math.h>
#include <plstream.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "PngFigure.h"

namespace mrpt_vslam::eval {
namespace {

constexpr int kRobotColors[] = {PngFigure::kBlue, PngFigure::kGreen, PngFigure::kPurple,
                                PngFigure::kBrown};

int estimateColor(size_t robot) { return kRobotColors[robot % std::size(kRobotColors)]; }
/// Odometry is orange for one robot, else the robot's colour (drawn dashed).
int odometryColor(const core::TEvalResult& r, size_t robot)
{
    return r.robots.size() == 1 ? PngFigure::kOrange : estimateColor(robot);
}

std::string labelOf(const core::TRobotResult& r, const std::string& what)
{
    return r.files.robot.empty() ? what : r.files.robot + " " + what;
}

/// Growing [min, max] box of the points drawn.
struct TBounds {
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    void add(double x, double y)
    {
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    /// Adds a relative margin (and a minimum span of 1 m) on every side.
    void pad(double rel)
    {
        const double mx = std::max(1.0, x1 - x0) * rel, my = std::max(1.0, y1 - y0) * rel;
        x0 -= mx, x1 += mx, y0 -= my, y1 += my;
    }
};

/// XY of a path, optionally moved by the trajectory's SE(2) alignment.
void pathXY(const core::TTrajectoryResult& t, bool aligned, std::vector<double>& x,
            std::vector<double>& y)
{
    for (const auto& p : t.path.poses) {
        const auto q = aligned ? core::applySE2(t.aligned.alignment, p) : p;
        x.push_back(q.x);
        y.push_back(q.y);
    }
}

void landmarkXY(const std::vector<core::TLandmark>& lms, const mrpt::math::TPose2D& move,
                std::vector<double>& x, std::vector<double>& y)
{
    for (const auto& l : lms) {
        const auto q = core::applySE2(move, {l.position.x, l.position.y, 0, 0, 0, 0});
        x.push_back(q.x);
        y.push_back(q.y);
    }
}

}  // namespace

void plotPaths(const core::TEvalResult& result, bool aligned, const std::string& file)
{
    // Aligning the map only makes sense with one robot (one transform).
    const bool alignMap = aligned && result.robots.size() == 1;
    const mrpt::math::TPose2D mapMove =
        alignMap ? result.robots[0].estimate.aligned.alignment : mrpt::math::TPose2D{0, 0, 0};
    struct TSeries {
        std::vector<double> x, y;
        int color, style;
    };
    std::vector<TSeries> lines;
    TBounds b;
    for (size_t k = 0; k < result.robots.size(); k++) {
        const auto& r = result.robots[k];
        TSeries gt{{}, {}, PngFigure::kBlack, 1};
        for (const auto& p : r.ground_truth.poses) gt.x.push_back(p.x), gt.y.push_back(p.y);
        lines.push_back(gt);
        if (r.odometry) {
            TSeries odo{{}, {}, odometryColor(result, k), 2};
            pathXY(*r.odometry, aligned, odo.x, odo.y);
            lines.push_back(odo);
        }
        TSeries est{{}, {}, estimateColor(k), 1};
        pathXY(r.estimate, aligned, est.x, est.y);
        lines.push_back(est);
    }
    std::vector<double> tx, ty, ex, ey;
    if (result.true_landmarks) landmarkXY(result.true_landmarks->landmarks, {0, 0, 0}, tx, ty);
    if (result.map) landmarkXY(result.map->landmarks, mapMove, ex, ey);
    for (const auto& s : lines)
        for (size_t i = 0; i < s.x.size(); i++) b.add(s.x[i], s.y[i]);
    for (size_t i = 0; i < tx.size(); i++) b.add(tx[i], ty[i]);
    for (size_t i = 0; i < ex.size(); i++) b.add(ex[i], ey[i]);
    b.pad(0.05);

    // The legend goes in the free column right of the plot; the page is as tall as the
    // equal-aspect plot needs (wide maps get a low page), with room for the legend, and fixed
    // margins in pixels for the tick labels, the axis labels and the title.
    const double bottomPx = 90, topPx = 45;
    const double plotHeightPx = 1200 * 0.54 * (b.y1 - b.y0) / (b.x1 - b.x0) + bottomPx + topPx;
    const int heightPx = static_cast<int>(std::clamp(plotHeightPx, 480.0, 800.0));
    PngFigure fig(file, 1200, heightPx);
    fig.axes(0.1, 0.64, bottomPx / heightPx, 1 - topPx / heightPx, b.x0, b.x1, b.y0, b.y1, "x [m]",
             "y [m]", aligned ? "Paths (estimate SE(2)-aligned to ground truth)" : "Paths", true);
    if (result.landmarks)  // thin links from each true landmark to its matched estimate
        for (const auto& m : result.landmarks->matches)
            if (m.matched())
                fig.line({m.true_position.x, ex[m.est_index]}, {m.true_position.y, ey[m.est_index]},
                         PngFigure::kGray, 1, 1.0);
    for (const auto& s : lines) fig.line(s.x, s.y, s.color, s.style);
    fig.markers(tx, ty, PngFigure::kBlack, "+", 1.4);
    fig.markers(ex, ey, PngFigure::kRed, "×", 1.4);

    fig.addLegend("ground truth", PngFigure::kBlack, 1);
    for (size_t k = 0; k < result.robots.size(); k++) {
        const auto& r = result.robots[k];
        fig.addLegend(labelOf(r, "estimate"), estimateColor(k), 1);
        if (r.odometry) fig.addLegend(labelOf(r, "odometry"), odometryColor(result, k), 2);
    }
    if (!tx.empty()) fig.addLegend("true landmarks", PngFigure::kBlack, 0, "+");
    if (!ex.empty())
        fig.addLegend(result.map->is_view_map ? "map views" : "estimated landmarks",
                      PngFigure::kRed, 0, "×");
    fig.drawLegend(PL_POSITION_TOP | PL_POSITION_RIGHT | PL_POSITION_INSIDE | PL_POSITION_SUBPAGE);
    fig.commit();
}

void plotErrors(const core::TEvalResult& result, bool aligned, const std::string& file)
{
    double t0 = std::numeric_limits<double>::infinity(), t1 = -t0, eMax = 0, hMax = 0;
    const auto metricsOf =
        [aligned](const core::TTrajectoryResult& t) -> const core::TTrajectoryMetrics& {
        return aligned ? t.aligned : t.unaligned;
    };
    std::vector<std::pair<const core::TTrajectoryResult*, size_t>> series;  // (trajectory, robot)
    for (size_t k = 0; k < result.robots.size(); k++) {
        const auto& r = result.robots[k];
        series.emplace_back(&r.estimate, k);
        if (r.odometry) series.emplace_back(&*r.odometry, k);
        t0 = std::min(t0, r.ground_truth.timestamps.front());
        t1 = std::max(t1, r.ground_truth.timestamps.back());
    }
    for (const auto& [t, k] : series) {
        const auto& m = metricsOf(*t);
        eMax = std::max(eMax, m.ate_max);
        hMax = std::max(hMax, mrpt::RAD2DEG(m.heading_max));
    }
    if (!(t1 > t0)) t1 = t0 + 1;
    eMax = std::max(eMax, 1e-3) * 1.35;
    hMax = std::max(hMax, 0.1) * 1.35;

    PngFigure fig(file, 1000, 800);
    const std::string how = aligned ? " (SE(2)-aligned)" : "";
    for (int panel = 0; panel < 2; panel++) {
        const bool pos = panel == 0;
        if (pos)
            fig.axes(0.12, 0.95, 0.6, 0.93, 0, t1 - t0, 0, eMax, "time since start [s]",
                     "position error [m]", "Position error" + how);
        else
            fig.axes(0.12, 0.95, 0.1, 0.43, 0, t1 - t0, -hMax, hMax, "time since start [s]",
                     "heading error [deg]", "Heading error (estimate - truth)" + how);
        for (const auto& [t, k] : series) {
            const auto& m = metricsOf(*t);
            const bool odo = t != &result.robots[k].estimate;
            std::vector<double> x, y;
            for (size_t i = 0; i < m.timestamps.size(); i++) {
                x.push_back(m.timestamps[i] - t0);
                y.push_back(pos ? m.position_errors[i] : mrpt::RAD2DEG(m.heading_errors[i]));
            }
            const int color = odo ? odometryColor(result, k) : estimateColor(k);
            fig.line(x, y, color, odo ? 2 : 1);
            if (pos)
                fig.addLegend(labelOf(result.robots[k], odo ? "odometry" : "estimate"), color,
                              odo ? 2 : 1);
        }
        if (pos) fig.drawLegend(PL_POSITION_TOP | PL_POSITION_LEFT | PL_POSITION_INSIDE);
    }
    fig.commit();
}

void plotLandmarkErrors(const core::TLandmarkMetrics& metrics, const std::string& file)
{
    const size_t n = metrics.matches.size();
    double yMax = metrics.cutoff;
    for (const auto& m : metrics.matches)
        if (m.matched()) yMax = std::max(yMax, m.error_norm);
    yMax *= 1.3;

    PngFigure fig(file, 1000, 600);
    fig.axes(0.1, 0.95, 0.12, 0.9, -0.5, std::max<double>(n, 1) - 0.5, 0, yMax,
             "true landmark (index in the ground-truth file)", "position error [m]",
             "Landmark error after one-to-one matching");
    const double half = n > 60 ? 0.5 : 0.35;
    std::vector<double> mx, my;
    fig.pl().col0(PngFigure::kBlue);
    for (size_t i = 0; i < n; i++) {
        const auto& m = metrics.matches[i];
        if (!m.matched()) {
            mx.push_back(static_cast<double>(i));
            my.push_back(0.03 * yMax);
            continue;
        }
        const double x0 = i - half, x1 = i + half, bx[] = {x0, x1, x1, x0},
                     by[] = {0, 0, m.error_norm, m.error_norm};
        fig.pl().fill(4, bx, by);
    }
    fig.markers(mx, my, PngFigure::kRed, "×", 1.4);
    const double xr = std::max<double>(n, 1) - 0.5;
    fig.line({-0.5, xr}, {metrics.cutoff, metrics.cutoff}, PngFigure::kGray, 2, 1.5);
    if (metrics.num_matched > 0)
        fig.line({-0.5, xr}, {metrics.error_mean, metrics.error_mean}, PngFigure::kGreen, 3, 1.5);

    fig.addLegend("error of the matched estimate", PngFigure::kBlue, 1);
    if (metrics.num_matched > 0) fig.addLegend("mean error", PngFigure::kGreen, 3);
    fig.addLegend("matching cut-off", PngFigure::kGray, 2);
    if (!mx.empty()) fig.addLegend("missed (no estimate matched)", PngFigure::kRed, 0, "×");
    fig.drawLegend(PL_POSITION_TOP | PL_POSITION_RIGHT | PL_POSITION_INSIDE);
    fig.commit();
}

}  // namespace mrpt_vslam::eval
