#pragma once

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace mrpt_vslam::test {

/// A JSON file of a run folder (run.json, metrics.json), parsed.
inline nlohmann::json readJson(const std::string& file)
{
    std::ifstream in(file);
    return nlohmann::json::parse(in);
}

/// A file's bytes (to compare outputs of two runs).
inline std::string readBytes(const std::string& file)
{
    std::ifstream in(file, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace mrpt_vslam::test
