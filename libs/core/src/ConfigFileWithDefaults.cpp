#include <mrpt_vslam/core/ConfigFileWithDefaults.h>

#include <stdexcept>
#include <utility>

namespace mrpt_vslam::core {

ConfigFileWithDefaults::ConfigFileWithDefaults(const mrpt::config::CConfigFileBase& config,
                                               std::string section,
                                               std::map<std::string, std::string> defaults)
    : m_config(config), m_section(std::move(section)), m_defaults(std::move(defaults))
{
}

void ConfigFileWithDefaults::getAllSections(std::vector<std::string>& sections) const
{
    m_config.getAllSections(sections);
}

void ConfigFileWithDefaults::getAllKeys(const std::string& section,
                                        std::vector<std::string>& keys) const
{
    m_config.getAllKeys(section, keys);
}

void ConfigFileWithDefaults::clear()
{
    throw std::logic_error("ConfigFileWithDefaults: read-only");
}

void ConfigFileWithDefaults::writeString(const std::string&, const std::string&, const std::string&)
{
    throw std::logic_error("ConfigFileWithDefaults: read-only");
}

std::string ConfigFileWithDefaults::readString(const std::string& section, const std::string& name,
                                               const std::string& defaultStr,
                                               bool failIfNotFound) const
{
    const auto given = m_defaults.find(name);
    if (section != m_section || given == m_defaults.end() || m_config.keyExists(section, name))
        return m_config.read_string(section, name, defaultStr, failIfNotFound);
    return m_config.read_string(section, name, given->second);
}

}  // namespace mrpt_vslam::core
