#pragma once

#include <mrpt/config/CConfigFileMemory.h>

#include <map>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace mrpt_vslam::core {

/** One `--set SECTION.KEY=VALUE` override of a configuration key. */
struct TConfigOverride {
    std::string section;
    std::string key;
    std::string value;

    /** Parses "SECTION.KEY=VALUE". The key is what follows the last dot before the first '='
     *  (keys never contain dots; sections may). VALUE may be empty. Throws UsageError naming
     *  the text when a part is missing or the key contains spaces. */
    static TConfigOverride parse(const std::string& text);
    std::string asString() const;  ///< "SECTION.KEY=VALUE"
};

/** A key the program asked for, and what its reader wanted (told by the default text MRPT's
 *  typed readers pass to readString(), see CheckedConfigFile). */
struct TReadKey {
    enum class Kind {
        Real,              ///< read_double, read_float: a finite number
        Integer,           ///< read_int, read_uint64_t
        IntegerOrBoolean,  ///< read_bool (or an integer read with default 0 or 1)
        Text               ///< read_string: not checked
    };
    std::string section;  ///< as the program asked for it
    std::string key;
    Kind kind = Kind::Text;
    /// the value of its first read that succeeded: the configuration's (`configured`) or the
    /// default the program passed; empty while no read succeeded
    std::string value;
    bool configured = false;
    bool has_value = false;
};

/** A key of the configuration that nothing read: probably a typo. */
struct TUnreadKey {
    std::string section;
    std::string key;
    int line = 0;             ///< 1-based line in the file, 0 if it only comes from `--set`
    bool overridden = false;  ///< set (or changed) by `--set`
};

/** An MRPT configuration that catches typos: it holds the `.ini` text with the `--set`
 *  overrides applied and records every (section, key) read through it. Every MRPT reader
 *  (`read_*`, `MRPT_LOAD_CONFIG_VAR`, `CLoadableOptions::loadFromConfigFile`) ends in
 *  readString(), so after the program has loaded all its options, any key nothing asked for is
 *  unknown.
 *
 *  Usage:
 *  1. `cfg.loadFile(args.configFile, args.overrides);` (throws UsageError if the file is missing)
 *  2. load every option from `cfg` as from any `CConfigFileBase`;
 *  3. `cfg.throwIfUnreadKeys();` (throws UsageError listing each unknown key with its line);
 *  4. `cfg.writeEffectiveConfig(out.file("config.ini"));` and put effectiveText() in run.json.
 *
 *  Values are checked against the type asked for, which MRPT's readers tell by the default
 *  text they pass to readString(): a finite number for read_double / read_float, an integer for
 *  read_int / read_uint64_t (`1e12` and `1.5` are errors, where MRPT would read 1), an integer
 *  or true / false / yes / no for read_bool; read_string's text is not checked unless its
 *  default looks like one of those. A line that is not `key = value`, a `[section]`, a comment
 *  or a preprocessor line makes the file an error.
 *
 *  Section and key names are case-insensitive, as in MRPT. The text goes through MRPT's
 *  config parser (`@define`, `${VAR}`, `$eval{}`, `$env{}`).
 */
class CheckedConfigFile : public mrpt::config::CConfigFileMemory {
  public:
    CheckedConfigFile() = default;

    /** Loads a file, replacing any previous content and read marks. */
    void loadFile(const std::string& file, const std::vector<TConfigOverride>& overrides = {});
    /** Loads text; `name` stands for the file in messages. */
    void loadText(const std::string& text, const std::string& name,
                  const std::vector<TConfigOverride>& overrides = {});

    const std::string& name() const { return m_name; }

    /** @name Unknown keys
     *  @{ */
    /** Keys present in the effective configuration that nothing read, in file order (keys only
     *  set by `--set` last). */
    std::vector<TUnreadKey> unreadKeys() const;
    /** Throws UsageError with one line per unread key:
     *  `"<file>: unknown key [Section] name (line N)"` or `"... (set by --set)"`. */
    void throwIfUnreadKeys() const;
    /** True if (section, key) was read (case-insensitive). */
    bool wasRead(const std::string& section, const std::string& key) const;
    /** Every key read so far, present in the text or not, in (section, key) order: the options
     *  the program has. */
    std::vector<TReadKey> readKeys() const;
    /** @} */

    /** The last value that did not fit its key's type (e.g. "t.ini: [S] n = 1.5: not an
     *  integer"), "" if none: MRPT's MRPT_LOAD_CONFIG_VAR_NO_DEFAULT replaces the error of a
     *  read with "Value for 'n' not found", so callers report this instead. */
    const std::string& valueError() const { return m_valueError; }

    /** The effective configuration (overrides applied, preprocessor resolved, comments
     *  dropped) as `.ini` text, opening with `#` lines naming the file and the overrides. */
    std::string effectiveText() const;
    /** Writes effectiveText() atomically to `file`. */
    void writeEffectiveConfig(const std::string& file) const;

    /** Every key read so far with the value it was read with, as `.ini` text: per section, the
     *  keys the configuration sets, then those at the program's defaults (after a comment line
     *  saying so; real numbers in the shortest text that reads back to the same value). Used
     *  as the configuration, it gives the program the same values. */
    std::string optionsInUseText() const;
    /** Writes optionsInUseText() atomically to `file`. */
    void writeOptionsInUse(const std::string& file) const;

  protected:
    std::string readString(const std::string& section, const std::string& name,
                           const std::string& defaultStr,
                           bool failIfNotFound = false) const override;

  private:
    using CConfigFileMemory::setContent;  // content changes go through loadFile/loadText

    using TKeyId = std::pair<std::string, std::string>;  ///< lower-case (section, key)
    static TKeyId keyId(const std::string& section, const std::string& key);

    std::string m_name;
    std::vector<TConfigOverride> m_overrides;
    std::map<TKeyId, int> m_line_of_key;  ///< first line of each key in the file text
    std::set<TKeyId> m_overridden;
    mutable std::map<TKeyId, TReadKey> m_read;
    mutable std::string m_valueError;
    mutable std::mutex m_read_mutex;
};

}  // namespace mrpt_vslam::core
