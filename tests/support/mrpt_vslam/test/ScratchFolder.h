#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace mrpt_vslam::test {

/** A per-process scratch folder under the system's temp dir (parallel test runs do not share
 *  files), created on construction and removed with its contents on destruction. */
class ScratchFolder {
  public:
    explicit ScratchFolder(const std::string& name)
        : m_path(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid())))
    {
        std::filesystem::create_directories(m_path);
    }
    ~ScratchFolder()
    {
        std::error_code ec;
        std::filesystem::remove_all(m_path, ec);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;

    const std::filesystem::path& path() const { return m_path; }
    /// `<folder>/<name>` as a string.
    std::string file(const std::string& name) const { return (m_path / name).string(); }
    /// Writes `text` to `<folder>/<name>` and returns its path.
    std::string write(const std::string& name, const std::string& text) const
    {
        const auto f = file(name);
        std::ofstream(f) << text;
        return f;
    }

  private:
    std::filesystem::path m_path;
};

/// One scratch folder for the whole test process, removed at exit.
inline const std::filesystem::path& processScratchFolder()
{
    static const ScratchFolder folder("mrpt_vslam_test");
    return folder.path();
}

}  // namespace mrpt_vslam::test
