#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

namespace mrpt_vslam::test {

/// The environment variable that names the folder of the full UTIAS MRCLAM dataset 7.
inline constexpr const char* kMrclamDirVariable = "MRPT_VSLAM_MRCLAM_DIR";

/** A data folder that is not part of the repository: its path, or why a test that needs it must
 *  skip (`missing` not empty). */
struct TExternalFolder {
    std::string path;
    std::string missing;
};

/** The folder of UTIAS MRCLAM dataset 7 (its `.dat` files) from MRPT_VSLAM_MRCLAM_DIR.
 *  Usage: `const auto d7 = mrclamDataset7();`
 *         `if (!d7.missing.empty()) GTEST_SKIP() << d7.missing;` */
inline TExternalFolder mrclamDataset7()
{
    TExternalFolder f;
    const char* dir = std::getenv(kMrclamDirVariable);
    if (!dir || !*dir) {
        f.missing = std::string("the full UTIAS MRCLAM dataset 7 is not shipped: set ") +
                    kMrclamDirVariable + " to its folder (doc/real-data.md)";
        return f;
    }
    f.path = dir;
    if (!std::filesystem::exists(f.path + "/Barcodes.dat"))
        f.missing = std::string(kMrclamDirVariable) + "=" + f.path +
                    ": no Barcodes.dat there (not an MRCLAM dataset folder)";
    return f;
}

}  // namespace mrpt_vslam::test
