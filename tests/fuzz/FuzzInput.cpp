#include "FuzzInput.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace mrpt_vslam::fuzz {

namespace {
struct TScratch {
    std::string path;
    TScratch()
    {
        std::string pattern =
            (std::filesystem::temp_directory_path() / "mrpt_vslam_fuzz_XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a scratch folder");
        path = pattern;
    }
    ~TScratch()
    {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
};
}  // namespace

std::string scratchFolder()
{
    static const TScratch scratch;
    return scratch.path;
}

std::string writeScratchFile(const std::string& name, const uint8_t* data, size_t size)
{
    const std::string file = scratchFolder() + "/" + name;
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) throw std::runtime_error(file + ": cannot write");
    return file;
}

}  // namespace mrpt_vslam::fuzz
