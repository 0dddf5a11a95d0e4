#pragma once

#include <cstddef>
#include <vector>

namespace mrpt_vslam::core {

/** How much higher one sensor's readings put the points it shares with another sensor than the
 *  other's readings put them (ours; doc/multirobot.md, "Checking the sensor poses"). A sensor
 *  stated higher or lower on the robot than it is raises or lowers every point it reads alike,
 *  which its own readings cannot show, but a second sensor's readings of the same points can.
 *  From the differences of the heights the two give each shared point: their median, and its
 *  standard error from their median absolute deviation (1.4826 MAD, a normal's σ, times
 *  √(π / 2n) for the median of n), so that a few points paired wrongly do not move either. */
struct TSensorHeightOffset {
    double dz = 0;      ///< [m] the median difference
    double std_dz = 0;  ///< [m] its standard error (+inf for fewer than two points)
    size_t points = 0;  ///< shared points

    static TSensorHeightOffset estimate(std::vector<double> dz);
};

}  // namespace mrpt_vslam::core
