#include <mrpt_vslam/core/Median.h>
#include <mrpt_vslam/core/SensorHeightOffset.h>

#include <cmath>
#include <limits>

namespace mrpt_vslam::core {

TSensorHeightOffset TSensorHeightOffset::estimate(std::vector<double> dz)
{
    TSensorHeightOffset o;
    o.points = dz.size();
    o.std_dz = std::numeric_limits<double>::infinity();
    if (dz.empty()) return o;
    o.dz = median(dz);
    if (dz.size() < 2) return o;
    for (double& d : dz) d = std::abs(d - o.dz);
    const double sigma = 1.4826 * median(dz);
    o.std_dz = sigma * std::sqrt(M_PI / (2.0 * static_cast<double>(o.points)));
    return o;
}

}  // namespace mrpt_vslam::core
