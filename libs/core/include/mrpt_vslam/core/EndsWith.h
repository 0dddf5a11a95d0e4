#pragma once

#include <string>

namespace mrpt_vslam::core {

/** Whether `s` ends with `suffix` (case sensitive; every string ends with ""). */
inline bool endsWith(const std::string& s, const std::string& suffix)
{
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace mrpt_vslam::core
