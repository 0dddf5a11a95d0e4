#include <gtest/gtest.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/UsageError.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

using mrpt_vslam::core::CheckedConfigFile;
using mrpt_vslam::core::TConfigOverride;
using mrpt_vslam::core::UsageError;

namespace {

const char* const kIni =
    "# example\n"               // 1
    "[Filter]\n"                // 2
    "sampleSize = 100\n"        // 3
    "sigma_xy = 0.05 // [m]\n"  // 4
    "\n"                        // 5
    "[Camera]\n"                // 6
    "fx = 400\n"                // 7
    "fxx = 401\n";              // 8

struct TFilterOptions : public mrpt::config::CLoadableOptions {
    int sampleSize = 10;
    double sigma_xy = 1.0;
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s) override
    {
        MRPT_LOAD_CONFIG_VAR(sampleSize, int, c, s);
        MRPT_LOAD_CONFIG_VAR(sigma_xy, double, c, s);
    }
};

std::string messageOf(const CheckedConfigFile& cfg)
{
    try {
        cfg.throwIfUnreadKeys();
    } catch (const UsageError& e) {
        return e.what();
    }
    return {};
}

}  // namespace

TEST(CheckedConfigFile, TypoIsReportedWithSectionAndLine)
{
    CheckedConfigFile cfg;
    cfg.loadText(kIni, "demo.ini");
    TFilterOptions opts;
    opts.loadFromConfigFile(cfg, "Filter");
    EXPECT_DOUBLE_EQ(cfg.read_double("Camera", "fx", 0), 400.0);

    const auto unread = cfg.unreadKeys();
    ASSERT_EQ(unread.size(), 1u);
    EXPECT_EQ(unread[0].section, "Camera");
    EXPECT_EQ(unread[0].key, "fxx");
    EXPECT_EQ(unread[0].line, 8);
    EXPECT_EQ(messageOf(cfg), "demo.ini: unknown key [Camera] fxx (line 8)");
}

TEST(CheckedConfigFile, LoadConfigVarMarksKeysAsRead)
{
    CheckedConfigFile cfg;
    cfg.loadText(kIni, "demo.ini");
    EXPECT_FALSE(cfg.wasRead("Filter", "sampleSize"));
    TFilterOptions opts;
    opts.loadFromConfigFile(cfg, "Filter");
    EXPECT_EQ(opts.sampleSize, 100);
    EXPECT_DOUBLE_EQ(opts.sigma_xy, 0.05);
    EXPECT_TRUE(cfg.wasRead("Filter", "sampleSize"));
    EXPECT_TRUE(cfg.wasRead("FILTER", "SIGMA_XY"));  // case-insensitive, as MRPT
    EXPECT_FALSE(cfg.wasRead("Camera", "fx"));
}

TEST(CheckedConfigFile, EveryUnreadKeyIsListedInFileOrder)
{
    CheckedConfigFile cfg;
    cfg.loadText(kIni, "demo.ini");
    EXPECT_EQ(messageOf(cfg),
              "demo.ini: unknown key [Filter] sampleSize (line 3)\n"
              "demo.ini: unknown key [Filter] sigma_xy (line 4)\n"
              "demo.ini: unknown key [Camera] fx (line 7)\n"
              "demo.ini: unknown key [Camera] fxx (line 8)");
}

TEST(CheckedConfigFile, OverridesTakeEffectAndMayAddKeys)
{
    CheckedConfigFile cfg;
    cfg.loadText(kIni, "demo.ini",
                 {TConfigOverride::parse("Filter.sampleSize=250"),
                  TConfigOverride::parse("New.Section.gain=2.5")});
    TFilterOptions opts;
    opts.loadFromConfigFile(cfg, "Filter");
    EXPECT_EQ(opts.sampleSize, 250);
    EXPECT_DOUBLE_EQ(cfg.read_double("New.Section", "gain", 0), 2.5);
    cfg.read_int("Camera", "fx", 0);
    cfg.read_int("Camera", "fxx", 0);
    EXPECT_EQ(messageOf(cfg), "");
}

TEST(CheckedConfigFile, UnreadOverrideIsReportedAsSetOnCommandLine)
{
    CheckedConfigFile cfg;
    cfg.loadText(kIni, "demo.ini", {TConfigOverride::parse("Filter.sampleSise=5")});
    TFilterOptions opts;
    opts.loadFromConfigFile(cfg, "Filter");
    cfg.read_int("Camera", "fx", 0);
    cfg.read_int("Camera", "fxx", 0);
    EXPECT_EQ(opts.sampleSize, 100);
    EXPECT_EQ(messageOf(cfg), "demo.ini: unknown key [Filter] sampleSise (set by --set)");
}

TEST(CheckedConfigFile, OverrideParsingSplitsAtLastDot)
{
    const auto o = TConfigOverride::parse("MappingApplication.maps.x_count = 2 ");
    EXPECT_EQ(o.section, "MappingApplication.maps");
    EXPECT_EQ(o.key, "x_count");
    EXPECT_EQ(o.value, "2");
    EXPECT_EQ(TConfigOverride::parse("A.b=").value, "");
    EXPECT_EQ(TConfigOverride::parse("A.b=x=y").value, "x=y");
    EXPECT_THROW(TConfigOverride::parse("Ab=1"), UsageError);
    EXPECT_THROW(TConfigOverride::parse("A.b"), UsageError);
    EXPECT_THROW(TConfigOverride::parse(".b=1"), UsageError);
    EXPECT_THROW(TConfigOverride::parse("A.=1"), UsageError);
    EXPECT_THROW(TConfigOverride::parse("A.b c=1"), UsageError);
}

TEST(CheckedConfigFile, MissingFileIsNamed)
{
    CheckedConfigFile cfg;
    try {
        cfg.loadFile("/nonexistent/dir/app.ini");
        FAIL() << "no exception";
    } catch (const UsageError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "/nonexistent/dir/app.ini: cannot open configuration file");
    }
}

TEST(CheckedConfigFile, AFolderIsNotAConfigFile)
{
    CheckedConfigFile cfg;
    try {
        cfg.loadFile("/tmp");
        FAIL() << "no exception";
    } catch (const UsageError& e) {
        EXPECT_EQ(std::string(e.what()), "/tmp: a folder, not a configuration file");
    }
}

// A key the program requires (MRPT_LOAD_CONFIG_VAR_NO_DEFAULT, which replaces the reader's error
// with its own) is named as missing, with the sections the file has when its section is absent
// (a misspelt section name)
TEST(CheckedConfigFile, ARequiredKeyOrSectionThatIsMissingIsNamed)
{
    struct TRequired : public mrpt::config::CLoadableOptions {
        int sampleSize = 0;
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                const std::string& s) override
        {
            MRPT_LOAD_CONFIG_VAR_NO_DEFAULT(sampleSize, int, c, s);
        }
    };
    const auto errorOf = [](const std::string& text, const std::string& section) {
        CheckedConfigFile cfg;
        cfg.loadText(text, "t.ini");
        TRequired options;
        try {
            options.loadFromConfigFile(cfg, section);
        } catch (const std::exception&) {
            return cfg.valueError();
        }
        return std::string("read");
    };
    EXPECT_EQ(errorOf("[Filter]\nsampelSize = 3\n", "Filter"),
              "t.ini: [Filter] sampleSize is missing (required)");
    EXPECT_EQ(errorOf("[Filters]\nsampleSize = 3\n[Camera]\nfx = 1\n", "Filter"),
              "t.ini: [Filter] sampleSize is missing (required); there is no section [Filter], "
              "the file has [Camera], [Filters]");
    EXPECT_EQ(errorOf("[Filter]\nsampleSize = 3\n", "Filter"), "read");
}

TEST(CheckedConfigFile, EffectiveConfigRoundTripsWithOverrides)
{
    const std::string file =
        ::testing::TempDir() + "CheckedConfigFile_effective_" + std::to_string(::getpid()) + ".ini";
    std::remove(file.c_str());
    CheckedConfigFile cfg;
    cfg.loadText(kIni, "demo.ini", {TConfigOverride::parse("Camera.fx=512")});
    cfg.writeEffectiveConfig(file);

    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), cfg.effectiveText());
    EXPECT_NE(text.str().find("# --set Camera.fx=512\n"), std::string::npos);

    CheckedConfigFile again;
    again.loadFile(file);
    EXPECT_EQ(again.read_int("Camera", "fx", 0), 512);
    EXPECT_EQ(again.read_int("Filter", "sampleSize", 0), 100);
    EXPECT_EQ(again.read_int("Camera", "fxx", 0), 401);
    std::remove(file.c_str());
}

TEST(CheckedConfigFile, ReloadingClearsReadMarks)
{
    CheckedConfigFile cfg;
    cfg.loadText("[A]\nx = 1\n", "a.ini");
    EXPECT_EQ(cfg.read_int("A", "x", 0), 1);
    cfg.loadText("[B]\ny = 2\n", "b.ini");
    EXPECT_FALSE(cfg.wasRead("A", "x"));
    EXPECT_FALSE(cfg.sectionExists("A"));
    EXPECT_EQ(messageOf(cfg), "b.ini: unknown key [B] y (line 2)");
}

TEST(CheckedConfigFile, ValuesThatDoNotFitTheirKeyAreErrors)
{
    struct TCase {
        const char* value;
        const char* error;  ///< "" if accepted
    };
    const auto read = [](const std::string& key, const std::string& value) -> std::string {
        CheckedConfigFile cfg;
        cfg.loadText("[S]\n" + key + " = " + value + "\n", "t.ini");
        try {
            if (key == "n") cfg.read_int("S", "n", 10);
            if (key == "big") cfg.read_uint64_t("S", "big", 10);
            if (key == "flag") cfg.read_bool("S", "flag", false);
            if (key == "x") cfg.read_double("S", "x", 0.5);
            if (key == "name") cfg.read_string("S", "name", "unnamed");
        } catch (const UsageError& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(read("n", "1e12"), "t.ini: [S] n = 1e12: not an integer");
    EXPECT_EQ(read("n", "1.5"), "t.ini: [S] n = 1.5: not an integer");
    EXPECT_EQ(read("n", "-3"), "");
    EXPECT_EQ(read("big", "12 // count"), "");
    EXPECT_EQ(read("big", "lots"), "t.ini: [S] big = lots: not an integer");
    EXPECT_EQ(read("flag", "maybe"),
              "t.ini: [S] flag = maybe: not a boolean (true, false) or an integer");
    EXPECT_EQ(read("flag", "True"), "");
    EXPECT_EQ(read("flag", "no"), "");
    EXPECT_EQ(read("x", "abc"), "t.ini: [S] x = abc: not a number");
    EXPECT_EQ(read("x", "0.5m"), "t.ini: [S] x = 0.5m: not a number");
    EXPECT_EQ(read("x", "-2.5e-3"), "");
    EXPECT_EQ(read("x", "nan"), "t.ini: [S] x = nan: not a finite number");
    EXPECT_EQ(read("x", "-inf"), "t.ini: [S] x = -inf: not a finite number");
    EXPECT_EQ(read("x", "1e400"), "t.ini: [S] x = 1e400: not a finite number");
    EXPECT_EQ(read("name", "anything at all"), "");  // text: no type

    // MRPT's loaders replace the message; the file keeps it
    CheckedConfigFile cfg;
    cfg.loadText("[S]\nn = 2.5\n", "t.ini");
    int n = 1;
    EXPECT_ANY_THROW(MRPT_LOAD_CONFIG_VAR_NO_DEFAULT(n, int, cfg, "S"));
    EXPECT_EQ(cfg.valueError(), "t.ini: [S] n = 2.5: not an integer");
    cfg.loadText("[S]\nn = 2\n", "t.ini");
    EXPECT_EQ(cfg.valueError(), "");
}

TEST(CheckedConfigFile, ReadKeysListsEveryKeyAskedForWithItsKind)
{
    CheckedConfigFile cfg;
    cfg.loadText("[S]\nx = 2\n", "t.ini");
    cfg.read_double("S", "x", 0.5);
    cfg.read_int("S", "absent", 3);
    cfg.read_bool("T", "flag", true);
    cfg.read_string("T", "name", "n");
    cfg.read_double("s", "X", 0.5);  // the same key (case-insensitive): listed once
    // a program default that is not finite is no error of the user's
    EXPECT_NO_THROW(cfg.read_double("T", "limit", std::numeric_limits<double>::infinity()));
    const auto keys = cfg.readKeys();
    using K = mrpt_vslam::core::TReadKey::Kind;
    const std::vector<std::tuple<std::string, std::string, K>> expected{
        {"S", "absent", K::Integer},
        {"S", "x", K::Real},
        {"T", "flag", K::IntegerOrBoolean},
        {"T", "limit", K::Real},
        {"T", "name", K::Text}};
    ASSERT_EQ(keys.size(), expected.size());
    for (size_t i = 0; i < keys.size(); i++)
        EXPECT_EQ(std::make_tuple(keys[i].section, keys[i].key, keys[i].kind), expected[i]) << i;
}

// Every key read, with the value it was read with; read back as the configuration, the file
// gives the same values whatever the program's defaults are.
TEST(CheckedConfigFile, OptionsInUseGiveTheSameValuesAsTheConfiguration)
{
    const auto readAll = [](const CheckedConfigFile& cfg, double scale) {
        std::ostringstream values;
        values.precision(17);
        values << cfg.read_double("S", "x", 0.5 * scale) << " "
               << cfg.read_double("S", "sigma", 0.1 * scale) << " "
               << cfg.read_double("S", "fov", 180 * scale) << " "
               << cfg.read_double("S", "tiny", -2.5e-9 * scale) << " "
               << cfg.read_float("S", "gain", 1.3f * static_cast<float>(scale)) << " "
               << cfg.read_int("S", "count", 3 * static_cast<int>(scale)) << " "
               << cfg.read_bool("T", "flag", scale == 1) << " "
               << cfg.read_string("T", "label", scale == 1 ? "" : "other") << " "
               << cfg.read_string("T", "name", "n") << " "
               << cfg.read_double("T", "limit", scale * std::numeric_limits<double>::infinity());
        return values.str();
    };
    CheckedConfigFile cfg;
    cfg.loadText("[S]\nx = 2 // [m]\n[T]\nname = abc\n", "t.ini",
                 {TConfigOverride::parse("S.count=7")});
    const std::string values = readAll(cfg, 1);
    cfg.read_double("s", "X", 9);  // the first read's value stands
    EXPECT_EQ(cfg.optionsInUseText(),
              "# Every key read from t.ini (with its --set overrides), with the value it was read "
              "with\n"
              "\n[S]\ncount = 7\nx = 2\n# not set: the program's defaults\nfov = 180\n"
              "gain = 1.3\nsigma = 0.1\ntiny = -2.5e-09\n"
              "\n[T]\nname = abc\n# not set: the program's defaults\nflag = 1\nlabel = \n"
              "limit = inf\n");

    CheckedConfigFile again;
    again.loadText(cfg.optionsInUseText(), "options.ini");
    EXPECT_EQ(readAll(again, 2), values);  // other defaults: the file sets every key
    EXPECT_TRUE(again.unreadKeys().empty());
}

TEST(CheckedConfigFile, LinesThatAreNotKeysSectionsOrCommentsAreErrors)
{
    CheckedConfigFile cfg;
    EXPECT_NO_THROW(cfg.loadText("; c\n# c\n// c\n@define A 1\n\n[S]\nk = v\nempty =\n", "t.ini"));
    for (const char* text : {"[S]\nk = v\nthis is not ini\n", "[S\nk = v\n", "[S]\n= v\n",
                             "@include other.ini\n[S]\nk = v\n"}) {
        try {
            cfg.loadText(text, "t.ini");
            ADD_FAILURE() << text;
        } catch (const UsageError& e) {
            EXPECT_NE(std::string(e.what()).find("t.ini: line "), std::string::npos) << e.what();
        }
    }
}

// MRPT's preprocessor reads ${NAME} of @define; an error of it names the file, as a usage error.
TEST(CheckedConfigFile, PreprocessorErrorsNameTheFile)
{
    CheckedConfigFile cfg;
    cfg.loadText("@define N 7\n[S]\nk = ${N}\n", "t.ini");
    EXPECT_EQ(cfg.read_int("S", "k", 0), 7);
    for (const char* text : {"[S]\nk = ${NOPE}\n", "[S]\nk = $eval{2+}\n"}) {
        try {
            cfg.loadText(text, "t.ini");
            ADD_FAILURE() << text;
        } catch (const UsageError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind("t.ini: ", 0), 0u) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
}

// A config saved by a Windows editor (line endings CR LF, a UTF-8 byte order mark before a
// section or a comment) reads as the same file with Unix line endings and no mark.
TEST(CheckedConfigFile, WindowsLineEndingsAndByteOrderMarkReadAsUnixText)
{
    for (const std::string first : {"", "[Filter]\n"}) {
        std::string windows = "\xEF\xBB\xBF";
        for (const char c : first + kIni + "[Names]\nlabel = OMNICAM\n")
            windows += c == '\n' ? std::string("\r\n") : std::string(1, c);
        CheckedConfigFile cfg;
        cfg.loadText(windows, "windows.ini");
        TFilterOptions opts;
        opts.loadFromConfigFile(cfg, "Filter");
        EXPECT_EQ(opts.sampleSize, 100);
        EXPECT_DOUBLE_EQ(opts.sigma_xy, 0.05);
        EXPECT_DOUBLE_EQ(cfg.read_double("Camera", "fx", 0), 400.0);
        EXPECT_EQ(cfg.read_string("Names", "label", ""), "OMNICAM");
        EXPECT_EQ(messageOf(cfg), "windows.ini: unknown key [Camera] fxx (line " +
                                      std::to_string(first.empty() ? 8 : 9) + ")");
    }
}

// A key set twice in a section (in one [section] or in two of the same name, in any case) is an
// error naming both lines: MRPT's reader would take the last one without a word.
TEST(CheckedConfigFile, AKeySetTwiceIsAnError)
{
    for (const char* text :
         {"[Filter]\nsampleSize = 10\nsampleSize = 3\n",
          "[Filter]\nsampleSize = 10\n[Camera]\nfx = 1\n[Filter]\nSAMPLESIZE = 3\n"}) {
        CheckedConfigFile cfg;
        try {
            cfg.loadText(text, "twice.ini");
            ADD_FAILURE() << text;
        } catch (const UsageError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind("twice.ini: [Filter] ", 0), 0u) << what;
            EXPECT_NE(what.find(" is set twice (lines 2 and "), std::string::npos) << what;
        }
    }
    CheckedConfigFile cfg;  // the same key in two sections is two keys
    EXPECT_NO_THROW(cfg.loadText("[A]\nk = 1\n[B]\nk = 2\n", "two.ini"));
}
