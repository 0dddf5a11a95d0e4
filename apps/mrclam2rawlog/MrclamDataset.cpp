#include "MrclamDataset.h"

#include <mrpt/core/format.h>
#include <mrpt_vslam/core/TextColumns.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace mrpt_vslam::mrclam {
namespace {

// What the collection's robots (iRobot Create, Leung et al. 2011) and room can produce; values
// beyond are corrupt data, refused rather than converted.
constexpr double kMaxSpeed = 2.0;       // [m/s] commanded forward speed
constexpr double kMaxTurnRate = 10.0;   // [rad/s] commanded turn rate
constexpr double kMaxRange = 50.0;      // [m] a barcode reading
constexpr double kMaxDuration = 86400;  // [s] from a file's first time to any other file's time

/** The data lines of a table file with `columns` numbers each, passed to `row(values, where)`
 *  (`where` = "FILE:LINE: "). A file without data lines is an error. */
template <class ROW>
void readTable(const std::string& file, size_t columns, const std::string& layout, ROW&& row)
{
    std::ifstream in(file);
    if (!in) throw std::runtime_error(file + ": cannot open file");
    std::string line;
    size_t rows = 0;
    for (int line_number = 1; std::getline(in, line); line_number++) {
        if (core::isCommentOrBlank(line)) continue;
        const std::string where = file + ":" + std::to_string(line_number) + ": ";
        const std::vector<double> v = core::parseNumbers(line, where);
        if (v.size() != columns)
            throw std::runtime_error(where + "expected " + std::to_string(columns) + " columns '" +
                                     layout + "', got " + std::to_string(v.size()));
        row(v, where);
        rows++;
    }
    if (rows == 0) throw std::runtime_error(file + ": no data lines ('" + layout + "')");
}

/// `value` (named `what`, in `unit`) must lie in [low, high].
void checkRange(double value, double low, double high, const std::string& what,
                const std::string& unit, const std::string& where)
{
    if (value < low || value > high)
        throw std::runtime_error(where +
                                 mrpt::format("%s %g %s is implausible (must be in [%g, %g])",
                                              what.c_str(), value, unit.c_str(), low, high));
}

int integerColumn(double value, const std::string& what, const std::string& where)
{
    if (value != std::floor(value) || std::abs(value) > 1e9)
        throw std::runtime_error(where + what + " must be an integer");
    return static_cast<int>(value);
}

/** Times of a robot file must not go back (the readers rely on time order) and must stay within
 *  kMaxDuration of the dataset's first time (`first`, set by the first time read). */
void checkTime(double t, double& last, double& first, const std::string& where)
{
    if (t < last) throw std::runtime_error(where + "time goes back");
    if (!std::isfinite(first)) first = t;
    if (std::abs(t - first) > kMaxDuration)
        throw std::runtime_error(where + mrpt::format("time %.3f s is %.0f s away from the "
                                                      "dataset's first time; a dataset spans less "
                                                      "than a day",
                                                      t, std::abs(t - first)));
    last = t;
}

/// `first`: the dataset's first time read so far (NaN before any), shared by all files.
TMrclamRobot loadRobot(const std::string& dir, int n, double& first)
{
    TMrclamRobot r;
    r.number = n;
    const std::string base = dir + "/Robot" + std::to_string(n) + "_";
    double last = -std::numeric_limits<double>::infinity();
    readTable(base + "Odometry.dat", 3, "time v w", [&](const auto& v, const auto& where) {
        checkTime(v[0], last, first, where);
        checkRange(v[1], -kMaxSpeed, kMaxSpeed, "speed", "m/s", where);
        checkRange(v[2], -kMaxTurnRate, kMaxTurnRate, "turn rate", "rad/s", where);
        r.commands.push_back({v[0], v[1], v[2]});
    });
    last = -std::numeric_limits<double>::infinity();
    readTable(base + "Measurement.dat", 4, "time barcode range bearing",
              [&](const auto& v, const auto& where) {
                  checkTime(v[0], last, first, where);
                  const int barcode = integerColumn(v[1], "barcode", where);
                  if (barcode < 0)
                      throw std::runtime_error(where + "barcode " + std::to_string(barcode) +
                                               " must be >= 0");
                  if (!(v[2] > 0)) throw std::runtime_error(where + "range must be > 0 m");
                  checkRange(v[2], 0, kMaxRange, "range", "m", where);
                  checkRange(v[3], -2 * M_PI, 2 * M_PI, "bearing", "rad", where);
                  r.readings.push_back({v[0], barcode, v[2], v[3]});
              });
    last = -std::numeric_limits<double>::infinity();
    readTable(base + "Groundtruth.dat", 4, "time x y theta", [&](const auto& v, const auto& where) {
        checkTime(v[0], last, first, where);
        r.ground_truth.push_back({v[0], {v[1], v[2], v[3]}});
    });
    return r;
}

}  // namespace

TMrclamDataset TMrclamDataset::load(const std::string& dir, const std::vector<int>& robot_numbers)
{
    if (!std::filesystem::is_directory(dir))
        throw std::runtime_error(dir + ": no such dataset folder");
    TMrclamDataset d;
    const auto subject = [](double value, const std::string& where) {
        const int s = integerColumn(value, "subject", where);
        if (s < 1 || s > kLastSubject)
            throw std::runtime_error(where + "subject " + std::to_string(s) + " is not in 1.." +
                                     std::to_string(kLastSubject));
        return s;
    };
    readTable(dir + "/Barcodes.dat", 2, "subject barcode", [&](const auto& v, const auto& where) {
        const int barcode = integerColumn(v[1], "barcode", where);
        if (!d.subject_of_barcode.emplace(barcode, subject(v[0], where)).second)
            throw std::runtime_error(where + "repeated barcode " + std::to_string(barcode));
    });
    readTable(dir + "/Landmark_Groundtruth.dat", 5, "subject x y std_x std_y",
              [&](const auto& v, const auto& where) {
                  const int s = subject(v[0], where);
                  if (s <= kRobots)
                      throw std::runtime_error(where + "subject " + std::to_string(s) +
                                               " is a robot, not a landmark");
                  if (!d.landmarks.emplace(s, mrpt::math::TPoint2D(v[1], v[2])).second)
                      throw std::runtime_error(where + "repeated subject " + std::to_string(s));
              });
    double first = std::numeric_limits<double>::quiet_NaN();
    for (int n : robot_numbers) d.robots.push_back(loadRobot(dir, n, first));
    return d;
}

double TMrclamDataset::firstTime() const
{
    double t = std::numeric_limits<double>::infinity();
    for (const TMrclamRobot& r : robots) {
        if (!r.commands.empty()) t = std::min(t, r.commands.front().t);
        if (!r.readings.empty()) t = std::min(t, r.readings.front().t);
        if (!r.ground_truth.empty()) t = std::min(t, r.ground_truth.front().t);
    }
    return t;
}

void TMrclamDataset::delayCommands(double seconds)
{
    for (TMrclamRobot& r : robots)
        for (TSpeedCommand& c : r.commands) c.t += seconds;
}

}  // namespace mrpt_vslam::mrclam
