#pragma once

#include <mrpt/config/CConfigFileBase.h>

#include <map>
#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** A configuration read through another: a key of `section` that the other does not set reads
 *  as the value `defaults` gives it, if any, as though the other set it. For MRPT's loaders
 *  that require keys (`MRPT_LOAD_CONFIG_VAR_NO_DEFAULT`, `read_*(..., failIfNotFound)`) whose
 *  recommended value the program knows. Every read goes through the other configuration with
 *  the default's text as its default, so a CheckedConfigFile records the key as read, at that
 *  value. Writing is not supported. */
class ConfigFileWithDefaults : public mrpt::config::CConfigFileBase {
  public:
    /// \param defaults key → value text; `config` must outlive this object
    ConfigFileWithDefaults(const mrpt::config::CConfigFileBase& config, std::string section,
                           std::map<std::string, std::string> defaults);

    void getAllSections(std::vector<std::string>& sections) const override;
    void getAllKeys(const std::string& section, std::vector<std::string>& keys) const override;
    void clear() override;

  protected:
    void writeString(const std::string& section, const std::string& name,
                     const std::string& str) override;
    std::string readString(const std::string& section, const std::string& name,
                           const std::string& defaultStr,
                           bool failIfNotFound = false) const override;

  private:
    const mrpt::config::CConfigFileBase& m_config;
    std::string m_section;
    std::map<std::string, std::string> m_defaults;
};

}  // namespace mrpt_vslam::core
