#pragma once

#include <string>
#include <vector>

namespace mrpt_vslam::eval {

/** Named series of (x, y) points, optionally with a [low, high] band per point, read from a
 *  whitespace-separated text table: one point per line, `SERIES X Y` or `SERIES X Y LOW HIGH`,
 *  `#` comments and blank lines skipped. Series keep the order of their first line; points keep
 *  file order. */
struct SeriesTable {
    struct TSeries {
        std::string name;
        std::vector<double> x, y, low, high;  ///< low/high empty, or one per point
    };
    std::vector<TSeries> series;

    /// \throw std::runtime_error "FILE:LINE: problem" for unreadable files, malformed or
    /// non-finite numbers, a series mixing lines with and without a band, or no points.
    static SeriesTable load(const std::string& file);
};

}  // namespace mrpt_vslam::eval
