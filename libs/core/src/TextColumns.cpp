#include <mrpt_vslam/core/TextColumns.h>
#include <mrpt_vslam/core/UsageError.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mrpt_vslam::core {

std::vector<double> parseNumbers(const std::string& line, const std::string& where)
{
    std::istringstream ss(line);
    std::vector<double> values;
    std::string token;
    while (ss >> token) {
        size_t used = 0;
        double v = 0;
        try {
            v = std::stod(token, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != token.size())
            throw std::runtime_error(where + "'" + token + "' is not a number");
        if (!std::isfinite(v)) throw std::runtime_error(where + "non-finite value");
        values.push_back(v);
    }
    return values;
}

std::vector<double> readNumberList(const mrpt::config::CConfigFileBase& cfg,
                                   const std::string& section, const std::string& key,
                                   const std::vector<double>& default_values)
{
    if (!cfg.keyExists(section, key)) return default_values;
    std::string text = cfg.read_string(section, key, "");
    std::replace(text.begin(), text.end(), ',', ' ');
    try {
        return parseNumbers(text, "[" + section + "] " + key + ": ");
    } catch (const std::runtime_error& e) {
        throw UsageError(e.what());
    }
}

bool isCommentOrBlank(const std::string& line)
{
    const auto first = line.find_first_not_of(" \t\r");
    return first == std::string::npos || line[first] == '#';
}

}  // namespace mrpt_vslam::core
