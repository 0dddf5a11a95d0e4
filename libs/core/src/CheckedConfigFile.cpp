#include <mrpt/core/format.h>
#include <mrpt/system/string_utils.h>
#include <mrpt_vslam/core/AtomicFile.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/UsageError.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <tuple>
#include <utility>

namespace mrpt_vslam::core {
namespace {

std::string toLower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

bool startsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

/** Line of the first appearance of each (lower-case section, key) in INI text, with the same
 *  rules as MRPT's reader: `[section]` headers, `key = value` lines, and comment (`;`, `#`,
 *  `//`) and preprocessor (`@define`, MRPT 2.5's only directive) lines skipped. Keys before any
 *  header belong to "". Any other line is an error naming `name` and the line (MRPT's reader
 *  passes over another `@` directive without a word), and so is a key set twice in a section
 *  (MRPT's reader would take the last one without a word). */
std::map<std::pair<std::string, std::string>, int> keyLines(const std::string& text,
                                                            const std::string& name)
{
    std::map<std::pair<std::string, std::string>, int> lines;
    std::istringstream in(text);
    std::string raw, section, section_as_written;
    for (int line_no = 1; std::getline(in, raw); ++line_no) {
        if (!raw.empty() && raw.back() == '\r') raw.pop_back();  // Windows line endings
        const std::string line = mrpt::system::trim(raw);
        if (line.empty() || line[0] == ';' || line[0] == '#' || startsWith(line, "//")) continue;
        if (line[0] == '@') {
            if (startsWith(line, "@define ") || startsWith(line, "@define\t")) continue;
            throw UsageError(name + ": line " + std::to_string(line_no) + ": " +
                             line.substr(0, line.find_first_of(" \t")) +
                             " is not a directive MRPT's configs know (@define NAME VALUE)");
        }
        const auto close = line.find(']');
        if (line[0] == '[' && close != std::string::npos) {
            section_as_written = mrpt::system::trim(line.substr(1, close - 1));
            section = toLower(section_as_written);
            continue;
        }
        const auto eq = line.find('=');
        if (line[0] == '[' || eq == std::string::npos || eq == 0)
            throw UsageError(name + ": line " + std::to_string(line_no) +
                             " is not `key = value`, a [section] or a comment");
        const std::string key = mrpt::system::trim(line.substr(0, eq));
        const auto [at, added] = lines.emplace(std::make_pair(section, toLower(key)), line_no);
        if (!added)
            throw UsageError(name + ": [" + section_as_written + "] " + key +
                             " is set twice (lines " + std::to_string(at->second) + " and " +
                             std::to_string(line_no) + ")");
    }
    return lines;
}

using TValueKind = TReadKey::Kind;

/** What MRPT's typed readers ask for, told by the default text they pass to readString():
 *  read_double "%.16e", read_float "%.10e", read_int "%i", read_uint64_t "%lu", read_bool "1"
 *  or "0"; anything else is read_string's own default. */
TValueKind kindOfDefault(const std::string& d)
{
    static const std::regex integer(R"([+-]?[0-9]+)");
    static const std::regex real(R"(-?([0-9]\.[0-9]+e[+-][0-9]+|inf|nan|-nan))");
    if (d == "0" || d == "1") return TValueKind::IntegerOrBoolean;
    if (std::regex_match(d, integer)) return TValueKind::Integer;
    if (std::regex_match(d, real)) return TValueKind::Real;
    return TValueKind::Text;
}

/// Why `value` cannot be read as `kind` ("" if it can).
std::string typeError(TValueKind kind, const std::string& value)
{
    static const std::regex integer(R"([+-]?([0-9]+|0[xX][0-9a-fA-F]+))");
    static const std::regex boolean(R"(true|false|yes|no)", std::regex::icase);
    char* end = nullptr;
    const double x = std::strtod(value.c_str(), &end);
    const bool number = !value.empty() && *end == '\0';
    switch (kind) {
        case TValueKind::Real:
            return !number ? "not a number" : std::isfinite(x) ? "" : "not a finite number";
        case TValueKind::Integer:
            return std::regex_match(value, integer) ? "" : "not an integer";
        case TValueKind::IntegerOrBoolean:
            if (std::regex_match(value, integer) || std::regex_match(value, boolean)) return "";
            return number ? "not an integer" : "not a boolean (true, false) or an integer";
        case TValueKind::Text:
            break;
    }
    return "";
}

}  // namespace

TConfigOverride TConfigOverride::parse(const std::string& text)
{
    const auto fail = [&](const std::string& why) {
        throw UsageError("--set " + text + ": " + why + " (expected SECTION.KEY=VALUE)");
    };
    const auto eq = text.find('=');
    if (eq == std::string::npos) fail("missing '='");
    const std::string lhs = text.substr(0, eq);
    const auto dot = lhs.rfind('.');
    if (dot == std::string::npos) fail("missing '.' between section and key");
    TConfigOverride o;
    o.section = mrpt::system::trim(lhs.substr(0, dot));
    o.key = mrpt::system::trim(lhs.substr(dot + 1));
    o.value = mrpt::system::trim(text.substr(eq + 1));
    if (o.section.empty()) fail("empty section");
    if (o.key.empty()) fail("empty key");
    if (o.section.find_first_of("[]") != std::string::npos) fail("brackets in the section name");
    if (o.key.find_first_of(" \t") != std::string::npos) fail("blank in the key name");
    return o;
}

std::string TConfigOverride::asString() const { return section + "." + key + "=" + value; }

CheckedConfigFile::TKeyId CheckedConfigFile::keyId(const std::string& section,
                                                   const std::string& key)
{
    return {toLower(section), toLower(key)};
}

void CheckedConfigFile::loadFile(const std::string& file,
                                 const std::vector<TConfigOverride>& overrides)
{
    if (std::filesystem::is_directory(file))
        throw UsageError(file + ": a folder, not a configuration file");
    std::ifstream in(file);
    if (!in) throw UsageError(file + ": cannot open configuration file");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw UsageError(file + ": cannot read configuration file");
    loadText(text.str(), file, overrides);
}

void CheckedConfigFile::loadText(const std::string& text, const std::string& name,
                                 const std::vector<TConfigOverride>& overrides)
{
    clear();
    m_valueError.clear();
    // the byte order mark some Windows editors start a UTF-8 file with is not part of line 1
    const std::string bom = "\xEF\xBB\xBF";
    const std::string content = text.rfind(bom, 0) == 0 ? text.substr(bom.size()) : text;
    try {  // MRPT's preprocessor: @define, ${NAME}, $eval{...}, $env{...}
        CConfigFileMemory::setContent(content);
    } catch (const std::exception& e) {
        throw UsageError(name + ": " + oneLineMessage(e));
    }
    m_name = name;
    m_overrides = overrides;
    m_line_of_key = keyLines(content, name);
    m_overridden.clear();
    for (const auto& o : overrides) {
        CConfigFileMemory::writeString(o.section, o.key, o.value);
        m_overridden.insert(keyId(o.section, o.key));
    }
    std::lock_guard<std::mutex> lock(m_read_mutex);
    m_read.clear();
}

std::string CheckedConfigFile::readString(const std::string& section, const std::string& name,
                                          const std::string& defaultStr, bool failIfNotFound) const
{
    const TValueKind kind = kindOfDefault(defaultStr);
    {
        std::lock_guard<std::mutex> lock(m_read_mutex);
        TReadKey read;
        read.section = section;
        read.key = name;
        read.kind = kind;
        m_read.emplace(keyId(section, name), std::move(read));
    }
    std::string value;
    try {
        value = CConfigFileMemory::readString(section, name, defaultStr, failIfNotFound);
    } catch (const std::exception&) {  // a key the program needs is not there
        std::vector<std::string> sections;
        getAllSections(sections);
        std::string present;
        for (const auto& s : sections) present += (present.empty() ? "[" : ", [") + s + "]";
        m_valueError =
            m_name + ": [" + section + "] " + name + " is missing (required)" +
            (sectionExists(section) ? ""
                                    : "; there is no section [" + section + "], the file has " +
                                          (present.empty() ? "none" : present));
        throw UsageError(m_valueError);
    }
    // the program's own default is not the user's to fix (it may be e.g. "inf")
    const std::string why = value == defaultStr ? "" : typeError(kind, mrpt::system::trim(value));
    if (!why.empty()) {
        m_valueError =
            m_name + ": [" + section + "] " + name + " = " + mrpt::system::trim(value) + ": " + why;
        throw UsageError(m_valueError);
    }
    {
        const TKeyId id = keyId(section, name);
        const bool configured = m_line_of_key.count(id) != 0 || m_overridden.count(id) != 0;
        std::lock_guard<std::mutex> lock(m_read_mutex);
        auto& read = m_read.at(id);
        if (!read.has_value) {
            read.configured = configured;
            read.value = read.configured ? mrpt::system::trim(value) : defaultStr;
            read.has_value = true;
        }
    }
    return value;
}

bool CheckedConfigFile::wasRead(const std::string& section, const std::string& key) const
{
    std::lock_guard<std::mutex> lock(m_read_mutex);
    return m_read.count(keyId(section, key)) != 0;
}

std::vector<TReadKey> CheckedConfigFile::readKeys() const
{
    std::lock_guard<std::mutex> lock(m_read_mutex);
    std::vector<TReadKey> keys;
    for (const auto& [id, read] : m_read) keys.push_back(read);
    return keys;
}

std::vector<TUnreadKey> CheckedConfigFile::unreadKeys() const
{
    std::vector<TUnreadKey> unread;
    std::vector<std::string> sections, keys;
    getAllSections(sections);
    for (const auto& section : sections) {
        getAllKeys(section, keys);
        for (const auto& key : keys) {
            if (wasRead(section, key)) continue;
            const auto id = keyId(section, key);
            const auto line = m_line_of_key.find(id);
            unread.push_back({section, key, line == m_line_of_key.end() ? 0 : line->second,
                              m_overridden.count(id) != 0});
        }
    }
    std::sort(unread.begin(), unread.end(), [](const TUnreadKey& a, const TUnreadKey& b) {
        return std::make_tuple(a.line == 0, a.line, a.section, a.key) <
               std::make_tuple(b.line == 0, b.line, b.section, b.key);
    });
    return unread;
}

void CheckedConfigFile::throwIfUnreadKeys() const
{
    const auto unread = unreadKeys();
    if (unread.empty()) return;
    std::string msg;
    for (const auto& u : unread) {
        if (!msg.empty()) msg += '\n';
        msg += m_name + ": unknown key [" + u.section + "] " + u.key;
        if (u.line > 0)
            msg += " (line " + std::to_string(u.line) + (u.overridden ? ", set by --set)" : ")");
        else
            msg += " (set by --set)";
    }
    throw UsageError(msg);
}

std::string CheckedConfigFile::effectiveText() const
{
    std::string text = "# Effective configuration of " + m_name + "\n";
    for (const auto& o : m_overrides) text += "# --set " + o.asString() + "\n";
    return text + getContent();
}

void CheckedConfigFile::writeEffectiveConfig(const std::string& file) const
{
    AtomicFile out(file);
    out.stream() << effectiveText();
    out.commit();
}

namespace {
/// A real default in the shortest text that reads back to the same value: a double's
/// (read_double's "%.16e") or a float's (read_float's "%.10e"); any other default as it is.
std::string defaultText(const TReadKey& key)
{
    if (key.kind != TReadKey::Kind::Real) return key.value;
    const double x = std::strtod(key.value.c_str(), nullptr);
    if (!std::isfinite(x)) return key.value;
    const size_t sign = key.value[0] == '-' ? 1 : 0;
    const bool single = key.value.find('e') == sign + 12;  // "-d.dddddddddde±xx"
    const auto same = [&](double y) {
        return single ? static_cast<float>(y) == static_cast<float>(x) : y == x;
    };
    // no exponent for numbers that read well without one (180, not 1.8e+02)
    const bool plain = x == 0 || (std::abs(x) >= 1e-4 && std::abs(x) < 1e15);
    for (int digits = 1;; digits++) {
        const std::string text = mrpt::format("%.*g", digits, x);
        const bool readable = !plain || text.find('e') == std::string::npos;
        if (digits == 17 || (readable && same(std::strtod(text.c_str(), nullptr)))) return text;
    }
}
}  // namespace

std::string CheckedConfigFile::optionsInUseText() const
{
    std::string text = "# Every key read from " + m_name +
                       (m_overrides.empty() ? "" : " (with its --set overrides)") +
                       ", with the value it was read with\n";
    std::map<std::string, std::vector<TReadKey>> bySection;  // lower-case section: its keys
    for (const auto& key : readKeys())
        if (key.has_value) bySection[toLower(key.section)].push_back(key);
    for (const auto& [id, keys] : bySection) {
        text += "\n[" + keys.front().section + "]\n";
        for (const auto& key : keys)
            if (key.configured) text += key.key + " = " + key.value + "\n";
        bool first = true;
        for (const auto& key : keys) {
            if (key.configured) continue;
            if (std::exchange(first, false)) text += "# not set: the program's defaults\n";
            text += key.key + " = " + defaultText(key) + "\n";
        }
    }
    return text;
}

void CheckedConfigFile::writeOptionsInUse(const std::string& file) const
{
    AtomicFile out(file);
    out.stream() << optionsInUseText();
    out.commit();
}

}  // namespace mrpt_vslam::core
