#include <mrpt/core/format.h>
#include <mrpt_vslam/core/OptionChecks.h>

#include <stdexcept>

namespace mrpt_vslam::core {

void requireKey(bool ok, const std::string& section, std::string_view key, std::string_view what)
{
    if (!ok)
        throw std::invalid_argument("[" + section + "] " + std::string(key) + ": " +
                                    std::string(what));
}

void requireOption(bool ok, std::string_view key, std::string_view what)
{
    if (!ok) throw std::invalid_argument(std::string(key) + " " + std::string(what));
}

void requireParameter(bool ok, std::string_view owner, std::string_view key, double value,
                      std::string_view requirement)
{
    if (!ok)
        throw std::invalid_argument(std::string(owner) + ": " + std::string(key) + " = " +
                                    mrpt::format("%g", value) + " " + std::string(requirement));
}

}  // namespace mrpt_vslam::core
