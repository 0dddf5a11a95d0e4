#pragma once

#include <exception>
#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** The message of an exception as one line for the user: MRPT exceptions carry a banner, the
 *  location and a call stack; this keeps only their "Message:" text (the innermost one when
 *  nested). Other exceptions give what() with newlines replaced by spaces. */
std::string oneLineMessage(const std::exception& e);

/** Alternatives as a message lists them: "a", "a or b", "a, b or c". */
std::string listOfChoices(const std::vector<std::string>& names);

}  // namespace mrpt_vslam::core
