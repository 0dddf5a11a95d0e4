// vslam-plot: draws the series of a text table (SeriesTable) as lines with markers and optional
// error bands, or as points against the line y = x, into a PNG (the figures of
// scripts/reproduce-*.sh).
#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/TclapParse.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/core/Version.h>
#include <plstream.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>

#include "PngFigure.h"
#include "SeriesTable.h"

using mrpt_vslam::eval::PngFigure;
using mrpt_vslam::eval::SeriesTable;

namespace {

constexpr int kColors[] = {PngFigure::kBlue, PngFigure::kOrange, PngFigure::kGreen,
                           PngFigure::kRed,  PngFigure::kPurple, PngFigure::kBrown,
                           PngFigure::kGray, PngFigure::kBlack};

struct TPlotOptions {
    std::string title, x_label, y_label;
    bool log_x = false, log_y = false, y_from_zero = false;
    bool points = false;    ///< markers only (a scatter plot)
    bool diagonal = false;  ///< the line y = x, on one range for both axes
};

void plot(const SeriesTable& table, const std::string& out, const TPlotOptions& o)
{
    if (o.y_from_zero && o.log_y)
        throw std::invalid_argument("--y-from-zero and --log-y exclude each other");
    const auto log_of = [](bool log, const char* flag, const std::string& series, double v) {
        if (!log) return v;
        if (!(v > 0))
            throw std::invalid_argument(std::string(flag) + ": series '" + series +
                                        "' has a value <= 0");
        return std::log10(v);
    };
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    std::vector<std::vector<double>> xs, ys, lows, highs;  // in plot coordinates
    for (const auto& s : table.series) {
        const auto Y = [&](double v) { return log_of(o.log_y, "--log-y", s.name, v); };
        auto& x = xs.emplace_back();
        auto& y = ys.emplace_back();
        auto& low = lows.emplace_back();
        auto& high = highs.emplace_back();
        for (size_t i = 0; i < s.x.size(); i++) {
            x.push_back(log_of(o.log_x, "--log-x", s.name, s.x[i]));
            y.push_back(Y(s.y[i]));
            if (!s.low.empty()) low.push_back(Y(s.low[i])), high.push_back(Y(s.high[i]));
            x0 = std::min(x0, x.back()), x1 = std::max(x1, x.back());
            y0 = std::min({y0, y.back(), low.empty() ? y.back() : low.back()});
            y1 = std::max({y1, y.back(), high.empty() ? y.back() : high.back()});
        }
    }
    if (o.diagonal) {
        if (o.log_x != o.log_y)
            throw std::invalid_argument("--diagonal needs both axes linear or both logarithmic");
        x0 = y0 = std::min(x0, y0);
        x1 = y1 = std::max(x1, y1);
    }
    if (o.y_from_zero) y0 = std::min(0.0, y0);
    const double mx = std::max(1e-9, x1 - x0) * 0.05, my = std::max(1e-9, y1 - y0) * 0.08;
    PngFigure fig(out, o.diagonal ? 760 : 1000, 700);  // square axes need no width to spare
    fig.axes(0.1, 0.95, 0.13, 0.92, x0 - mx, x1 + mx, o.y_from_zero && y0 >= 0 ? 0 : y0 - my,
             y1 + my, o.x_label, o.y_label, o.title, o.diagonal, o.log_x, o.log_y);
    if (o.diagonal) {
        fig.line({x0 - mx, x1 + mx}, {x0 - mx, x1 + mx}, PngFigure::kGray, 2, 1.5);
        fig.addLegend("y = x", PngFigure::kGray, 2);
    }
    for (size_t k = 0; k < table.series.size(); k++) {
        const int color = kColors[k % std::size(kColors)];
        for (size_t i = 0; i < lows[k].size(); i++)  // error bars
            fig.line({xs[k][i], xs[k][i]}, {lows[k][i], highs[k][i]}, color, 1, 1.5);
        if (!o.points) fig.line(xs[k], ys[k], color, 1);
        fig.markers(xs[k], ys[k], color, "•", 1.2);
        fig.addLegend(table.series[k].name, color, o.points ? 0 : 1, "•");
    }
    fig.drawLegend(o.diagonal ? PL_POSITION_TOP | PL_POSITION_LEFT | PL_POSITION_INSIDE
                              : PL_POSITION_TOP | PL_POSITION_RIGHT | PL_POSITION_INSIDE);
    fig.commit();
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        TCLAP::CmdLine cmd(
            "vslam-plot: line or scatter plot of the series in a text table.\n"
            "  vslam-plot TABLE.txt OUT.png [--title T] [--x-label L] [--y-label L] [--log-x]\n"
            "             [--log-y] [--points] [--diagonal]\n"
            "TABLE.txt: one point per line, 'SERIES X Y' or 'SERIES X Y LOW HIGH' (LOW HIGH: an "
            "error bar); '#' starts a comment.",
            ' ', mrpt_vslam::core::projectVersion());
        TCLAP::UnlabeledValueArg<std::string> table("TABLE", "Input table", true, "", "TABLE.txt",
                                                    cmd);
        TCLAP::UnlabeledValueArg<std::string> out("OUT", "Output PNG", true, "", "OUT.png", cmd);
        TCLAP::ValueArg<std::string> title("", "title", "Title", false, "", "T", cmd);
        TCLAP::ValueArg<std::string> xl("", "x-label", "x axis label", false, "x", "L", cmd);
        TCLAP::ValueArg<std::string> yl("", "y-label", "y axis label", false, "y", "L", cmd);
        TCLAP::SwitchArg logx("", "log-x", "Logarithmic x axis", cmd);
        TCLAP::SwitchArg logy("", "log-y", "Logarithmic y axis", cmd);
        TCLAP::SwitchArg zero("", "y-from-zero", "Start the y axis at 0", cmd);
        TCLAP::SwitchArg points("", "points", "Markers only, no lines (a scatter plot)", cmd);
        TCLAP::SwitchArg diagonal("", "diagonal",
                                  "Draw the line y = x, both axes on one range and scale", cmd);
        std::string message;
        if (mrpt_vslam::core::parseTclap(cmd, argc, argv, "vslam-plot", message) !=
            mrpt_vslam::core::TclapOutcome::Parsed) {
            std::cout << message;  // --help or --version
            return 0;
        }
        TPlotOptions o;
        o.title = title.getValue(), o.x_label = xl.getValue(), o.y_label = yl.getValue();
        o.log_x = logx.getValue(), o.log_y = logy.getValue(), o.y_from_zero = zero.getValue();
        o.points = points.getValue(), o.diagonal = diagonal.getValue();
        plot(SeriesTable::load(table.getValue()), out.getValue(), o);
        return 0;
    } catch (const mrpt_vslam::core::UsageError& e) {
        std::cerr << "vslam-plot: error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "vslam-plot: error: " << mrpt_vslam::core::oneLineMessage(e) << "\n";
    }
    return 1;
}
