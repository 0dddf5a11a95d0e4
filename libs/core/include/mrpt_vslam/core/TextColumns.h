#pragma once

#include <mrpt/config/CConfigFileBase.h>

#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** The whitespace-separated numbers of one data line of a text file. Throws std::runtime_error
 *  starting with `where` (e.g. "FILE:LINE: ") on a token that is not a number or is not finite. */
std::vector<double> parseNumbers(const std::string& line, const std::string& where);

/** The whitespace- or comma-separated numbers of `[section] key` (commas as MRPT's read_vector
 *  takes them), or `default_values` when the key is absent. Throws UsageError
 *  "[section] key: 'x' is not a number" (or ": non-finite value"). */
std::vector<double> readNumberList(const mrpt::config::CConfigFileBase& cfg,
                                   const std::string& section, const std::string& key,
                                   const std::vector<double>& default_values);

/** Whether a line holds no data: empty, blanks only, or a `#` comment. */
bool isCommentOrBlank(const std::string& line);

}  // namespace mrpt_vslam::core
