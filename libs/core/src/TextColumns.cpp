#include <mrpt_vslam/core/TextColumns.h>

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

bool isCommentOrBlank(const std::string& line)
{
    const auto first = line.find_first_not_of(" \t\r");
    return first == std::string::npos || line[first] == '#';
}

}  // namespace mrpt_vslam::core
