#include <mrpt_vslam/core/OutputDirectory.h>

#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace mrpt_vslam::core {

OutputDirectory::OutputDirectory(const std::string& dir) : m_dir(dir)
{
    if (dir.empty()) throw std::runtime_error("output folder name is empty");
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (!ec && !std::filesystem::is_directory(dir, ec))
        ec = std::make_error_code(std::errc::not_a_directory);
    if (ec) throw std::runtime_error(dir + ": cannot create output folder: " + ec.message());
}

std::string OutputDirectory::file(const std::string& name) const
{
    return (std::filesystem::path(m_dir) / name).string();
}

}  // namespace mrpt_vslam::core
