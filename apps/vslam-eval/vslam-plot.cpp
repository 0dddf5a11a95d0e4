// vslam-plot: draws the series of a text table (SeriesTable) as lines with markers and optional
// error bands into a PNG (the figures of scripts/reproduce-*.sh).
#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt_vslam/core/ErrorMessage.h>
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

void plot(const SeriesTable& table, const std::string& out, const std::string& title,
          const std::string& x_label, const std::string& y_label, bool log_x, bool y_from_zero)
{
    const auto X = [&](double x) { return log_x ? std::log10(x) : x; };
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    for (const auto& s : table.series)
        for (size_t i = 0; i < s.x.size(); i++) {
            if (log_x && !(s.x[i] > 0))
                throw std::invalid_argument("--log-x: series '" + s.name + "' has x <= 0");
            x0 = std::min(x0, X(s.x[i])), x1 = std::max(x1, X(s.x[i]));
            y0 = std::min({y0, s.y[i], s.low.empty() ? s.y[i] : s.low[i]});
            y1 = std::max({y1, s.y[i], s.high.empty() ? s.y[i] : s.high[i]});
        }
    if (y_from_zero) y0 = std::min(0.0, y0);
    const double mx = std::max(1e-9, x1 - x0) * 0.05, my = std::max(1e-9, y1 - y0) * 0.08;
    PngFigure fig(out, 1000, 700);
    fig.axes(0.1, 0.95, 0.13, 0.92, x0 - mx, x1 + mx, y_from_zero && y0 >= 0 ? 0 : y0 - my, y1 + my,
             x_label, y_label, title, false, log_x);
    for (size_t k = 0; k < table.series.size(); k++) {
        const auto& s = table.series[k];
        const int color = kColors[k % std::size(kColors)];
        std::vector<double> x;
        for (const double v : s.x) x.push_back(X(v));
        for (size_t i = 0; i < s.low.size(); i++)  // error bars
            fig.line({x[i], x[i]}, {s.low[i], s.high[i]}, color, 1, 1.5);
        fig.line(x, s.y, color, 1);
        fig.markers(x, s.y, color, "•", 1.2);
        fig.addLegend(s.name, color, 1, "•");
    }
    fig.drawLegend(PL_POSITION_TOP | PL_POSITION_RIGHT | PL_POSITION_INSIDE);
    fig.commit();
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        TCLAP::CmdLine cmd(
            "vslam-plot: line plot of the series in a text table.\n"
            "  vslam-plot TABLE.txt OUT.png [--title T] [--x-label L] [--y-label L] [--log-x]\n"
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
        TCLAP::SwitchArg zero("", "y-from-zero", "Start the y axis at 0", cmd);
        cmd.parse(argc, argv);
        plot(SeriesTable::load(table.getValue()), out.getValue(), title.getValue(), xl.getValue(),
             yl.getValue(), logx.getValue(), zero.getValue());
        return 0;
    } catch (const TCLAP::ArgException& e) {
        std::cerr << "vslam-plot: error: " << e.argId() << ": " << e.error() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "vslam-plot: error: " << mrpt_vslam::core::oneLineMessage(e) << "\n";
    }
    return 1;
}
