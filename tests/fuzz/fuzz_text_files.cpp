// The text files the project reads, on any bytes: TUM trajectories (ground truth, estimates),
// landmark and map files, and each file of a UTIAS MRCLAM dataset folder as mrclam2rawlog reads
// it (the others of the folder valid). The first byte picks the file. Errors are exceptions; a
// crash or a hang is a bug.
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/TumTrajectory.h>

#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "FuzzInput.h"
#include "MrclamDataset.h"

namespace {
const char* const kMrclamFiles[] = {"Barcodes.dat", "Landmark_Groundtruth.dat",
                                    "Robot1_Odometry.dat", "Robot1_Measurement.dat",
                                    "Robot1_Groundtruth.dat"};

/// A valid two-second MRCLAM folder for robot 1 (landmark 6, barcode 23), written once.
std::string validMrclamFolder()
{
    static const std::string dir = [] {
        const std::string d = mrpt_vslam::fuzz::scratchFolder() + "/mrclam";
        std::filesystem::create_directories(d);
        std::ofstream(d + "/Barcodes.dat") << "# Subject # Barcode #\n1 5\n6 23\n";
        std::ofstream(d + "/Landmark_Groundtruth.dat") << "# Subject x y sx sy\n6 2.0 1.0 0 0\n";
        std::ofstream(d + "/Robot1_Odometry.dat") << "# t v w\n100.0 0.1 0.0\n101.0 0.1 0.2\n";
        std::ofstream(d + "/Robot1_Measurement.dat") << "# t s r b\n100.5 23 1.5 0.1\n";
        std::ofstream(d + "/Robot1_Groundtruth.dat") << "# t x y th\n100.0 0 0 0\n102.0 0.2 0 0\n";
        return d;
    }();
    return dir;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace mrpt_vslam;
    if (size == 0) return 0;
    const uint8_t which = data[0] % 7;
    data++;
    size--;
    try {
        if (which == 0) {
            (void)core::TumTrajectory::load(fuzz::writeScratchFile("input.tum", data, size));
        } else if (which == 1) {
            (void)core::LandmarkFile::load(fuzz::writeScratchFile("input.txt", data, size));
        } else {
            const std::string dir = validMrclamFolder();
            const std::string file = std::string("mrclam/") + kMrclamFiles[which - 2];
            const std::string path = fuzz::scratchFolder() + "/" + file;
            const std::string valid = [&] {
                std::ifstream in(path);
                return std::string(std::istreambuf_iterator<char>(in), {});
            }();
            fuzz::writeScratchFile(file, data, size);
            try {
                auto d = mrclam::TMrclamDataset::load(dir, {1});
                (void)d.firstTime();
            } catch (const std::exception&) {
            }
            std::ofstream(path) << valid;
        }
    } catch (const std::exception&) {
    }
    return 0;
}
