#pragma once

#include <memory>
#include <string>
#include <vector>

class plstream;

namespace mrpt_vslam::eval {

/** A PNG figure drawn with PLplot's `pngcairo` device. It is written to `FILE.tmp` and renamed to
 *  FILE by commit(), so an interrupted run leaves no partial image.
 *  Usage: 1. construct; 2. draw with pl() and the helpers; 3. drawLegend(); 4. commit(). */
class PngFigure {
  public:
    /// Colour indices of the figure's palette (PLplot cmap0).
    enum Color : int {
        kWhite = 0,
        kBlack,
        kBlue,
        kOrange,
        kGreen,
        kRed,
        kPurple,
        kBrown,
        kGray,
        kLightGray,
        kCount
    };

    /** Opens the figure; throws std::runtime_error "FILE: problem" when FILE.tmp is not writable.
     */
    PngFigure(const std::string& file, int width_px, int height_px);
    ~PngFigure();
    PngFigure(const PngFigure&) = delete;
    PngFigure& operator=(const PngFigure&) = delete;

    plstream& pl() { return *m_pl; }

    /// Sets the viewport (normalised page coordinates) and the world window, then draws a grid
    /// and the labelled axes. With log_x (log_y), x0, x1 and every x drawn (y) are log10 of the
    /// values.
    void axes(double vx0, double vx1, double vy0, double vy1, double x0, double x1, double y0,
              double y1, const std::string& x_label, const std::string& y_label,
              const std::string& title, bool equal_aspect = false, bool log_x = false,
              bool log_y = false);

    /// Polyline; `style` is a PLplot line style (1 solid, 2 dashed, 3 dotted...).
    void line(const std::vector<double>& x, const std::vector<double>& y, int color, int style = 1,
              double width = 2.0);
    /// A UTF-8 glyph (e.g. "+", "×") at each point.
    void markers(const std::vector<double>& x, const std::vector<double>& y, int color,
                 const char* glyph, double scale = 1.0);

    /// Adds a legend entry: a line (style > 0) and/or a glyph (non-null).
    void addLegend(const std::string& text, int color, int style, const char* glyph = nullptr);
    /// Draws the collected entries inside the current viewport at a PLplot position
    /// (PL_POSITION_* flags) and clears them.
    void drawLegend(int position);

    /// Finishes the image and renames it into place.
    void commit();

  private:
    struct TLegendEntry {
        std::string text;
        int color, style;
        const char* glyph;
    };
    std::string m_file, m_tmp;
    std::unique_ptr<plstream> m_pl;
    std::vector<TLegendEntry> m_legend;
    bool m_committed = false;
};

}  // namespace mrpt_vslam::eval
