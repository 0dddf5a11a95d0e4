#include <mrpt_vslam/core/ErrorMessage.h>

#include <algorithm>

namespace mrpt_vslam::core {

std::string oneLineMessage(const std::exception& e)
{
    std::string text = e.what();
    const std::string tag = "Message:";
    // MRPT nests messages outermost first; the last "Message:" is where the error arose.
    if (const auto pos = text.rfind(tag); pos != std::string::npos) {
        text = text.substr(pos + tag.size());
        text = text.substr(0, text.find('\n'));
    }
    // MRPT's exception wrapper (e.g. around a particle filter step): a banner, the message, then
    // the call stack
    const std::string banner = "==== MRPT exception ====";
    if (const auto pos = text.rfind(banner); pos != std::string::npos)
        text = text.substr(pos + banner.size());
    text = text.substr(0, text.find("Call stack backtrace:"));
    std::replace(text.begin(), text.end(), '\n', ' ');
    const auto first = text.find_first_not_of(" \t");
    const auto last = text.find_last_not_of(" \t");
    return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
}

std::string listOfChoices(const std::vector<std::string>& names)
{
    std::string list;
    for (size_t i = 0; i < names.size(); i++)
        list += (i == 0 ? "" : i + 1 < names.size() ? ", " : " or ") + names[i];
    return list;
}

}  // namespace mrpt_vslam::core
