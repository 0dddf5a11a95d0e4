#include <mrpt_vslam/core/SensorHeightOffset.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mrpt_vslam::core {

namespace {
double median(std::vector<double>& v)
{
    const size_t h = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(h), v.end());
    const double upper = v[h];
    if (v.size() % 2) return upper;
    return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(h)));
}
}  // namespace

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
