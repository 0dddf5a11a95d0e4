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

DatasetWriter::DatasetWriter(const std::string& out_prefix, bool with_images,
                             const std::vector<std::string>& image_labels, TPngCoding image_coding)
    : m_prefix(out_prefix),
      m_rawlog(out_prefix + ".rawlog"),
      m_rawlog_tmp(out_prefix + ".rawlog.tmp"),
      m_images_dir(out_prefix + "_Images"),
      m_image_coding(image_coding)
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
            for (const std::string& label : image_labels)
                if (file.rfind(label + "_", 0) == 0 && entry.path().extension() == ".png")
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

std::string DatasetWriter::imageFileName(const std::string& label, int frame,
                                         const std::string& suffix)
{
    std::ostringstream os;
    os << label << '_' << std::setw(6) << std::setfill('0') << frame << suffix << ".png";
    return os.str();
}

void DatasetWriter::writePng(const mrpt::img::CImage& image, const std::string& file,
                             TPngCoding coding)
{
    const std::string tmp = file + ".tmp.png";
    const cv::Mat& mat = image.asCvMatRef();
    std::vector<int> params{cv::IMWRITE_PNG_COMPRESSION, 9};
    if (coding == TPngCoding::HuffmanOnly)
        params.insert(params.end(),
                      {cv::IMWRITE_PNG_STRATEGY, cv::IMWRITE_PNG_STRATEGY_HUFFMAN_ONLY});
    if (!cv::imwrite(tmp, mat, params)) throw std::runtime_error(tmp + ": cannot write image");
    core::AtomicFile::commitRename(tmp, file);
}

void DatasetWriter::writeImage(const mrpt::img::CImage& image, const std::string& file_name)
{
    writePng(image, m_images_dir + "/" + file_name, m_image_coding);
}

void DatasetWriter::writeImageBesideRawlog(const mrpt::img::CImage& image,
                                           const std::string& suffix)
{
    writePng(image, m_prefix + "." + suffix + ".png", TPngCoding::Default);
}

void DatasetWriter::writeFrame(const mrpt::obs::CActionCollection& actions,
                               const mrpt::obs::CSensoryFrame& frame)
{
    auto ar = mrpt::serialization::archiveFrom(*m_rawlog_out);
    ar << actions << frame;
}

void DatasetWriter::writeObservation(const mrpt::obs::CObservation& observation)
{
    auto ar = mrpt::serialization::archiveFrom(*m_rawlog_out);
    ar << observation;
}

void DatasetWriter::commit(const std::vector<TTumFile>& trajectories,
                           const core::LandmarkFile& landmarks,
                           const std::string& landmarks_comment)
{
    // All or nothing: a failure removes the text files this commit already put in place.
    std::vector<std::string> written;
    try {
        for (const TTumFile& t : trajectories) {
            const std::string file = m_prefix + "." + t.name + ".tum";
            t.poses.save(file, t.header_comment);
            written.push_back(file);
        }
        landmarks.save(m_prefix + ".landmarks.txt", landmarks_comment);
        written.push_back(m_prefix + ".landmarks.txt");

        m_rawlog_out->close();
        if (m_rawlog_out->fileOpenCorrectly())
            throw std::runtime_error(m_rawlog_tmp + ": cannot close file");
        core::AtomicFile::commitRename(m_rawlog_tmp, m_rawlog);
    } catch (...) {
        for (const std::string& file : written) std::remove(file.c_str());
        throw;
    }
    m_committed = true;
}

}  // namespace mrpt_vslam::sim
