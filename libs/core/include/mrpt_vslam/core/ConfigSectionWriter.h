#pragma once

#include <mrpt/config/CConfigFileBase.h>

#include <string>

namespace mrpt_vslam::core {

/** Writes the keys of one section, each with a comment beside it, padded as MRPT's
 *  MRPT_SAVE_CONFIG_VAR_COMMENT does; for keys that are not a member's name (`max_theta_deg`)
 *  and members whose names clash with that macro's (`c`).
 *
 *  Usage, in a saveToConfigFile(cfg, section):
 *  `const ConfigSectionWriter put(cfg, section); put("width", width, "[px] image width");` */
class ConfigSectionWriter {
  public:
    ConfigSectionWriter(mrpt::config::CConfigFileBase& cfg, const std::string& section)
        : m_cfg(cfg), m_section(section)
    {
    }

    template <typename T>
    void operator()(const std::string& key, const T& value, const std::string& comment) const
    {
        m_cfg.write(m_section, key, value, mrpt::config::MRPT_SAVE_NAME_PADDING(),
                    mrpt::config::MRPT_SAVE_VALUE_PADDING(), comment);
    }

  private:
    mrpt::config::CConfigFileBase& m_cfg;
    std::string m_section;
};

}  // namespace mrpt_vslam::core
