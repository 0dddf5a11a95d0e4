#pragma once

#include <gtest/gtest.h>
#include <mrpt_vslam/test/RunFiles.h>

#include <cstddef>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>

namespace mrpt_vslam::test {

/// The text without the last column of each line.
inline std::string withoutLastColumn(const std::string& text)
{
    std::istringstream in(text);
    std::string out;
    for (std::string line; std::getline(in, line);)
        out += line.substr(0, line.find_last_of(' ')) + "\n";
    return out;
}

/// run.json's results without the times they hold (keys ending in `_s`, e.g. `smoothing_s`).
inline nlohmann::json withoutTimes(nlohmann::json results)
{
    for (auto it = results.begin(); it != results.end();)
        it = it.key().size() > 2 && it.key().substr(it.key().size() - 2) == "_s" ? results.erase(it)
                                                                                 : std::next(it);
    return results;
}

/** Expects the run folders `a` and `b` of two runs of one app to hold the same results: in
 *  run.json the same counts and results (not its timing, the results' times, command line or
 *  configuration), every other file byte for byte, but for the folders' names (metrics.json
 *  names the files it scored) and the last column of steps.txt (view-slam's step times); the
 *  files of `skip` are left out. Returns how many files were compared byte for byte. */
inline size_t expectSameRunFolders(const std::string& a, const std::string& b,
                                   const std::set<std::string>& skip = {})
{
    size_t compared = 0;
    for (const auto& entry : std::filesystem::directory_iterator(a)) {
        const std::string file = entry.path().filename().string();
        const std::string other = b + "/" + file;
        if (skip.count(file)) continue;
        EXPECT_TRUE(std::filesystem::exists(other)) << other;
        if (!std::filesystem::exists(other)) continue;
        if (file == "run.json") {
            const auto ja = readJson(entry.path().string()), jb = readJson(other);
            EXPECT_EQ(ja["counts"], jb["counts"]) << a;
            EXPECT_EQ(withoutTimes(ja["results"]), withoutTimes(jb["results"])) << a;
            continue;
        }
        std::string first = readBytes(entry.path().string());
        for (size_t at = first.find(a); at != std::string::npos; at = first.find(a, at + b.size()))
            first.replace(at, a.size(), b);
        std::string second = readBytes(other);
        if (file == "steps.txt") {
            first = withoutLastColumn(first);
            second = withoutLastColumn(second);
        }
        EXPECT_EQ(first, second) << a << ": " << file;
        compared++;
    }
    return compared;
}

}  // namespace mrpt_vslam::test
