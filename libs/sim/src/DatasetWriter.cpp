#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/AtomicFile.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/sim/DatasetWriter.h>

#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace mrpt_vslam::sim {

DatasetWriter::DatasetWriter(const std::string& out_prefix, bool with_images)
    : m_prefix(out_prefix),
      m_rawlog(out_prefix + ".rawlog"),
      m_rawlog_tmp(out_prefix + ".rawlog.tmp"),
      m_images_dir(out_prefix + "_Images")
{
    const fs::path parent = fs::path(out_prefix).parent_path();
    std::error_code ec;
    if (!parent.empty()) fs::create_directories(parent, ec);
    if (ec)
        throw std::runtime_error(parent.string() + ": cannot create directory: " + ec.message());
    if (with_images) {
        fs::create_directories(m_images_dir, ec);
        if (ec)
            throw std::runtime_error(m_images_dir + ": cannot create directory: " + ec.message());
        // Images of an earlier, longer run would otherwise stay beside the new ones.
        for (const auto& entry : fs::directory_iterator(m_images_dir)) {
            const std::string file = entry.path().filename().string();
            if (file.rfind("OMNICAM_", 0) == 0 && entry.path().extension() == ".png")
                fs::remove(entry.path());
        }
    }
    m_rawlog_out = std::make_unique<mrpt::io::CFileGZOutputStream>();
    if (!m_rawlog_out->open(m_rawlog_tmp, 9))
        throw std::runtime_error(m_rawlog_tmp + ": cannot create file for writing");
}

DatasetWriter::~DatasetWriter()
{
    if (!m_committed) {
        m_rawlog_out.reset();
        std::remove(m_rawlog_tmp.c_str());
    }
}

std::string DatasetWriter::imageFileName(int frame)
{
    std::ostringstream os;
    os << "OMNICAM_" << std::setw(6) << std::setfill('0') << frame << ".png";
    return os.str();
}

void DatasetWriter::writeImage(const mrpt::img::CImage& image, int frame)
{
    const std::string file = m_images_dir + "/" + imageFileName(frame);
    const std::string tmp = file + ".tmp.png";
    const cv::Mat& mat = image.asCvMatRef();
    if (!cv::imwrite(tmp, mat, {cv::IMWRITE_PNG_COMPRESSION, 9}))
        throw std::runtime_error(tmp + ": cannot write image");
    core::AtomicFile::commitRename(tmp, file);
}

void DatasetWriter::writeFrame(const mrpt::obs::CActionCollection& actions,
                               const mrpt::obs::CSensoryFrame& frame)
{
    auto ar = mrpt::serialization::archiveFrom(*m_rawlog_out);
    ar << actions << frame;
}

void DatasetWriter::commit(const core::TumTrajectory& ground_truth,
                           const core::TumTrajectory& odometry,
                           const std::vector<TCeilingLight>& lights)
{
    ground_truth.save(m_prefix + ".groundtruth.tum",
                      "ground truth: robot base pose in the world (timestamp x y z qx qy qz qw)");
    odometry.save(m_prefix + ".odometry.tum",
                  "dead reckoning of the noisy odometry from the true initial pose");

    core::LandmarkFile landmarks;
    for (const TCeilingLight& l : lights) {
        core::TLandmark lm;
        lm.id = l.id;
        lm.position = l.position;
        landmarks.landmarks.push_back(lm);
    }
    landmarks.save(m_prefix + ".landmarks.txt");

    m_rawlog_out->close();
    if (m_rawlog_out->fileOpenCorrectly())
        throw std::runtime_error(m_rawlog_tmp + ": cannot close file");
    core::AtomicFile::commitRename(m_rawlog_tmp, m_rawlog);
    m_committed = true;
}

}  // namespace mrpt_vslam::sim
