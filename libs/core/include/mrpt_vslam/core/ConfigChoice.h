#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/typemeta/TEnumType.h>
#include <mrpt_vslam/core/ErrorMessage.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mrpt_vslam::core {

/** The value of `[section] key`: the value of the choice (name, value) it names, or of an alias
 *  (other names of choices, not listed in messages); `current` when the key is absent (its
 *  name, the first choice with that value, is what the configuration records as the default).
 *  Any other value, an empty one too, throws std::invalid_argument "[section] key must be a, b
 *  or c, not 'x'". \pre `current` is the value of one of `choices` */
template <class T>
T readChoice(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
             const std::string& key, const std::vector<std::pair<std::string, T>>& choices,
             const T& current, const std::vector<std::pair<std::string, T>>& aliases = {})
{
    std::string currentName;
    for (const auto& [name, value] : choices)
        if (value == current && currentName.empty()) currentName = name;
    const std::string text = cfg.read_string(section, key, currentName);
    for (const auto* list : {&choices, &aliases})
        for (const auto& [name, value] : *list)
            if (text == name) return value;
    std::vector<std::string> names;
    for (const auto& choice : choices) names.push_back(choice.first);
    throw std::invalid_argument("[" + section + "] " + key + " must be " + listOfChoices(names) +
                                ", not '" + text + "'");
}

/** readChoice() of an MRPT enum: one of ENUM's names (as its mrpt::typemeta::TEnumType spells
 *  them) or the number of one, as CConfigFileBase::read_enum() takes them, where read_enum()
 *  names no choice for a name it does not know and passes any number on as a value of ENUM.
 *  `allowed` narrows the choices to those values (empty: all of ENUM's). */
template <class ENUM>
ENUM readEnum(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
              const std::string& key, ENUM current, const std::vector<ENUM>& allowed = {})
{
    std::vector<std::pair<std::string, ENUM>> names, numbers;
    for (const auto& [value, name] : mrpt::typemeta::TEnumType<ENUM>::getBimap()) {
        if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), value) == allowed.end())
            continue;
        names.emplace_back(name, value);
        numbers.emplace_back(std::to_string(static_cast<long long>(value)), value);
    }
    return readChoice(cfg, section, key, names, current, numbers);
}

}  // namespace mrpt_vslam::core
