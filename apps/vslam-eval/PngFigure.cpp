#include "PngFigure.h"

#include <mrpt_vslam/core/AtomicFile.h>
#include <plstream.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace mrpt_vslam::eval {
namespace {

constexpr double kCharScale = 0.9;  // of PLplot's default character height

constexpr int kPalette[PngFigure::kCount][3] = {
    {255, 255, 255}, {0, 0, 0},       {31, 119, 180}, {255, 127, 14},  {44, 160, 44},
    {214, 39, 40},   {148, 103, 189}, {140, 86, 75},  {127, 127, 127}, {215, 215, 215}};

}  // namespace

PngFigure::PngFigure(const std::string& file, int width_px, int height_px)
    : m_file(file), m_tmp(file + ".tmp")
{
    // PLplot exits the process on an unwritable file, so check first.
    if (!std::ofstream(m_tmp)) throw std::runtime_error(file + ": cannot create file for writing");
    m_pl = std::make_unique<plstream>();
    m_pl->sdev("pngcairo");
    m_pl->sfnam(m_tmp.c_str());
    m_pl->spage(0, 0, width_px, height_px, 0, 0);
    m_pl->scmap0n(kCount);
    for (int c = 0; c < kCount; c++) m_pl->scol0(c, kPalette[c][0], kPalette[c][1], kPalette[c][2]);
    m_pl->init();
    m_pl->adv(0);
    m_pl->schr(0, kCharScale);
}

PngFigure::~PngFigure()
{
    if (!m_committed) {
        m_pl.reset();
        std::remove(m_tmp.c_str());
    }
}

void PngFigure::axes(double vx0, double vx1, double vy0, double vy1, double x0, double x1,
                     double y0, double y1, const std::string& x_label, const std::string& y_label,
                     const std::string& title, bool equal_aspect, bool log_x, bool log_y)
{
    // Equal aspect: the largest viewport in the region where one metre is as long on both axes.
    if (equal_aspect)
        m_pl->vpas(vx0, vx1, vy0, vy1, (y1 - y0) / (x1 - x0));
    else
        m_pl->vpor(vx0, vx1, vy0, vy1);
    m_pl->wind(x0, x1, y0, y1);
    m_pl->col0(kLightGray);
    m_pl->width(1.0);
    m_pl->box(log_x ? "gl" : "g", 0, 0, log_y ? "gl" : "g", 0, 0);
    m_pl->col0(kBlack);
    m_pl->box(log_x ? "bclnst" : "bcnst", 0, 0, log_y ? "bclnstv" : "bcnstv", 0, 0);
    m_pl->lab(x_label.c_str(), y_label.c_str(), title.c_str());
}

void PngFigure::line(const std::vector<double>& x, const std::vector<double>& y, int color,
                     int style, double width)
{
    m_pl->col0(color);
    m_pl->lsty(style);
    m_pl->width(width);
    m_pl->line(static_cast<PLINT>(x.size()), x.data(), y.data());
    m_pl->lsty(1);
}

void PngFigure::markers(const std::vector<double>& x, const std::vector<double>& y, int color,
                        const char* glyph, double scale)
{
    m_pl->col0(color);
    m_pl->schr(0, scale);
    m_pl->string(static_cast<PLINT>(x.size()), x.data(), y.data(), glyph);
    m_pl->schr(0, kCharScale);
}

void PngFigure::addLegend(const std::string& text, int color, int style, const char* glyph)
{
    m_legend.push_back({text, color, style, glyph});
}

void PngFigure::drawLegend(int position)
{
    const auto n = static_cast<PLINT>(m_legend.size());
    if (n == 0) return;
    std::vector<PLINT> opts, colors, styles, symbolNumbers(n, 1), textColors(n, kBlack);
    std::vector<PLFLT> widths(n, 2.0), symbolScales(n, 1.0);
    std::vector<const char*> texts, glyphs;
    for (const auto& e : m_legend) {
        opts.push_back((e.style > 0 ? PL_LEGEND_LINE : 0) | (e.glyph ? PL_LEGEND_SYMBOL : 0));
        colors.push_back(e.color);
        styles.push_back(e.style > 0 ? e.style : 1);
        texts.push_back(e.text.c_str());
        glyphs.push_back(e.glyph ? e.glyph : "");
    }
    PLFLT w = 0, h = 0;
    m_pl->lsty(1);
    m_pl->legend(&w, &h, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX, position, 0.02, 0.02, 0.06,
                 kWhite, kBlack, 1, 0, 0, n, opts.data(), 1.0, 0.9, 2.0, 0.0, textColors.data(),
                 texts.data(), nullptr, nullptr, nullptr, nullptr, colors.data(), styles.data(),
                 widths.data(), colors.data(), symbolScales.data(), symbolNumbers.data(),
                 glyphs.data());
    m_legend.clear();
}

void PngFigure::commit()
{
    m_pl.reset();  // ends the stream, which writes the image
    core::AtomicFile::commitRename(m_tmp, m_file);
    m_committed = true;
}

}  // namespace mrpt_vslam::eval
