#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/typemeta/TEnumType.h>
#include <mrpt_vslam/core/ErrorMessage.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** The value of `[section] key`: one of ENUM's names (as its mrpt::typemeta::TEnumType spells
 *  them) or the number of one, as CConfigFileBase::read_enum() takes them; `defaultValue` when
 *  the key is absent. Any other value, an empty one too, throws std::invalid_argument "[section]
 *  key must be a, b or c, not 'x'", where read_enum() names no choice for a name it does not
 *  know and passes any number on as a value of ENUM. */
template <class ENUM>
ENUM readEnum(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
              const std::string& key, ENUM defaultValue)
{
    // the default's name, not "", is what the configuration's record of the read keeps
    const std::string text = cfg.read_string_first_word(
        section, key, mrpt::typemeta::TEnumType<ENUM>::value2name(defaultValue));
    const auto& names = mrpt::typemeta::TEnumType<ENUM>::getBimap();
    std::vector<std::string> choices;
    for (const auto& [value, name] : names) {
        if (text == name || text == std::to_string(static_cast<long long>(value))) return value;
        choices.push_back(name);
    }
    throw std::invalid_argument("[" + section + "] " + key + " must be " + listOfChoices(choices) +
                                ", not '" + text + "'");
}

}  // namespace mrpt_vslam::core
