#pragma once

#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** The whitespace-separated numbers of one data line of a text file. Throws std::runtime_error
 *  starting with `where` (e.g. "FILE:LINE: ") on a token that is not a number or is not finite. */
std::vector<double> parseNumbers(const std::string& line, const std::string& where);

/** Whether a line holds no data: empty, blanks only, or a `#` comment. */
bool isCommentOrBlank(const std::string& line);

}  // namespace mrpt_vslam::core
