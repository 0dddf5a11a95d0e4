#include <mrpt_vslam/core/ProgressReporter.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <utility>

namespace mrpt_vslam::core {
namespace {

/** "2.3 s" below a minute, "4 min 05 s" below an hour, "1 h 05 min" above. */
std::string formatDuration(double s)
{
    char buf[48];
    if (s < 59.95) {
        std::snprintf(buf, sizeof(buf), "%.1f s", s);
    } else if (s < 3600) {
        const long t = std::lround(s);
        std::snprintf(buf, sizeof(buf), "%ld min %02ld s", t / 60, t % 60);
    } else {
        const long t = std::lround(s / 60);
        std::snprintf(buf, sizeof(buf), "%ld h %02ld min", t / 60, t % 60);
    }
    return buf;
}

}  // namespace

ProgressReporter::ProgressReporter(std::string app_name, size_t total, bool quiet,
                                   std::ostream& out, TimeSource now, std::string unit,
                                   double min_interval_s)
    : m_app(std::move(app_name)),
      m_total(total),
      m_quiet(quiet),
      m_out(out),
      m_now(std::move(now)),
      m_unit(std::move(unit)),
      m_min_interval_s(min_interval_s),
      m_start(m_now())
{
}

ProgressReporter::ProgressReporter(std::string app_name, size_t total, bool quiet)
    : ProgressReporter(std::move(app_name), total, quiet, std::cerr)
{
    // Logs and pipes get a plain line every few seconds instead of '\r' redraws.
    if (!isatty(STDERR_FILENO)) {
        m_in_place = false;
        m_min_interval_s = 5.0;
    }
}

ProgressReporter::~ProgressReporter()
{
    if (m_in_place && m_drawn && !m_finished) m_out << '\n' << std::flush;
}

std::string ProgressReporter::formatLine(size_t done, double elapsed_s, bool final_line) const
{
    std::string line = "[" + m_app + "] " + m_unit + " " + std::to_string(done);
    char buf[64];
    if (m_total > 0) {
        const int percent =
            static_cast<int>(100.0 * static_cast<double>(done) / static_cast<double>(m_total));
        line += "/" + std::to_string(m_total) + " (" + std::to_string(percent) + "%)";
    }
    const bool rate_known = elapsed_s > 0 && done > 0;
    const double rate = rate_known ? static_cast<double>(done) / elapsed_s : 0.0;
    if (rate_known) {
        std::snprintf(buf, sizeof(buf), "  %.1f %ss/s", rate, m_unit.c_str());
        line += buf;
    }
    if (final_line)
        line += "  done in " + formatDuration(elapsed_s);
    else if (rate_known && m_total > 0 && done <= m_total)
        line += "  ETA " + formatDuration(static_cast<double>(m_total - done) / rate);
    return line;
}

void ProgressReporter::update(size_t done)
{
    if (m_quiet || m_finished) return;
    const auto now = m_now();
    if (m_drawn && std::chrono::duration<double>(now - m_last_draw).count() < m_min_interval_s)
        return;
    m_last_draw = now;
    draw(formatLine(done, std::chrono::duration<double>(now - m_start).count(), false));
}

void ProgressReporter::finish(size_t done)
{
    if (m_quiet || m_finished) return;
    draw(formatLine(done, std::chrono::duration<double>(m_now() - m_start).count(), true));
    if (m_in_place) m_out << '\n' << std::flush;
    m_finished = true;
}

void ProgressReporter::draw(const std::string& line)
{
    if (!m_in_place) {
        m_out << line << '\n' << std::flush;
        m_drawn = true;
        return;
    }
    // Blank out what is left of a longer previous line.
    const std::string pad(m_last_width > line.size() ? m_last_width - line.size() : 0, ' ');
    m_out << '\r' << line << pad << std::flush;
    m_last_width = line.size();
    m_drawn = true;
}

}  // namespace mrpt_vslam::core
