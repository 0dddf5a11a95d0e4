#include <mrpt_vslam/core/OutputDirectory.h>

#include <array>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace mrpt_vslam::core {

namespace fs = std::filesystem;

OutputDirectory::OutputDirectory(const std::string& dir) : m_dir(dir)
{
    if (dir.empty()) throw std::runtime_error("output folder name is empty");
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (!ec && !fs::is_directory(dir, ec)) ec = std::make_error_code(std::errc::not_a_directory);
    if (ec) throw std::runtime_error(dir + ": cannot create output folder: " + ec.message());
}

std::string OutputDirectory::file(const std::string& name) const
{
    return (fs::path(m_dir) / name).string();
}

bool OutputDirectory::isRunFile(const std::string& name)
{
    static constexpr std::array kNames = {"run.json",    "metrics.json",       "config.ini",
                                          "options.ini", "final.3Dscene",      "final_map.gz",
                                          "steps.txt",   "observations.txt",   "paths.png",
                                          "errors.png",  "landmark_errors.png"};
    for (const char* n : kNames)
        if (name == n) return true;
    // STEM.ext or STEM_<X>.ext
    const fs::path path(name);
    const std::string stem = path.stem().string(), ext = path.extension().string();
    const auto named = [&stem](const std::string& s) {
        return stem == s || (stem.size() > s.size() + 1 && stem.rfind(s + "_", 0) == 0);
    };
    if (ext == ".tum")
        for (const char* s : {"estimated_path", "odometry_path", "filter_path"})
            if (named(s)) return true;
    if (ext == ".txt")
        for (const char* s : {"map", "particle_map", "filter_map"})
            if (named(s)) return true;
    return false;
}

bool OutputDirectory::holdsRunFile(const std::string& file) const
{
    std::error_code ec;
    const fs::path path(file);
    return isRunFile(path.filename().string()) &&
           fs::equivalent(fs::absolute(path).parent_path(), m_dir, ec);
}

size_t OutputDirectory::removeEarlierRun() const
{
    std::error_code ec;
    std::vector<fs::path> files;
    for (fs::directory_iterator it(m_dir, ec), end; !ec && it != end; it.increment(ec))
        if (!it->is_directory() && isRunFile(it->path().filename().string()))
            files.push_back(it->path());
    if (ec) throw std::runtime_error(m_dir + ": cannot list the output folder: " + ec.message());
    for (const auto& f : files) {
        if (!fs::remove(f, ec) && ec)
            throw std::runtime_error(f.string() + ": cannot remove: " + ec.message());
    }
    return files.size();
}

}  // namespace mrpt_vslam::core
