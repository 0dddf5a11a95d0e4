#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace mrpt_vslam::core {

/// The median of `v` (the mean of the two middle values for an even count); `v` not empty.
inline double median(std::vector<double> v)
{
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    if (v.size() % 2) return *mid;
    return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

}  // namespace mrpt_vslam::core
