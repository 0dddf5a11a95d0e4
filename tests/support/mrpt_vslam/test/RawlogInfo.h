#pragma once

#include <map>
#include <sstream>
#include <string>

namespace mrpt_vslam::test {

/// `rawlog-edit --info` report: "Field name : value" lines, and the per-sensor occurrence counts
/// of the "Sensor (Label/Occurs/Rate/Durat.) : LABEL / N / ..." lines.
struct TRawlogInfo {
    std::map<std::string, std::string> fields;
    std::map<std::string, int> sensor_counts;
};

inline TRawlogInfo parseRawlogInfo(const std::string& text)
{
    const auto trim = [](const std::string& v) {
        const size_t a = v.find_first_not_of(' '), b = v.find_last_not_of(' ');
        return a == std::string::npos ? std::string() : v.substr(a, b - a + 1);
    };
    TRawlogInfo info;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        const size_t colon = line.find(" : ");
        if (colon == std::string::npos) continue;
        const std::string name = trim(line.substr(0, colon)), value = trim(line.substr(colon + 3));
        if (name.rfind("Sensor (Label", 0) == 0) {
            const size_t slash = value.find('/');
            info.sensor_counts[trim(value.substr(0, slash))] = std::stoi(value.substr(slash + 1));
        } else {
            info.fields[name] = value;
        }
    }
    return info;
}

}  // namespace mrpt_vslam::test
