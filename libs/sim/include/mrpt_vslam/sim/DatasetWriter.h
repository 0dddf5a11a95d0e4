#pragma once

#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/TumTrajectory.h>

#include <memory>
#include <string>
#include <vector>

namespace mrpt_vslam::sim {

/** One TUM file of a dataset: `NAME.<name>.tum` with a `#` header comment. */
struct TTumFile {
    std::string name;            ///< e.g. "groundtruth", "odometry_R2"
    core::TumTrajectory poses;   ///< one pose per rawlog step, same timestamps
    std::string header_comment;  ///< first `#` line of the file
};

/** zlib strategy of the PNG images in NAME_Images/: the default suits sparse images (mostly one
 *  value, as the IR blobs of sports-hall); Huffman-only coding suits camera images with pixel
 *  noise, where LZ77 finds few repeats (about 12 % smaller for the office-team images). */
enum class TPngCoding { Default, HuffmanOnly };

/** Writes a simulated dataset for `DIR/NAME` (doc/data-formats.md): `NAME.rawlog` in either rawlog
 *  format (action/sensory-frame pairs through writeFrame(), or observation-only through
 *  writeObservation()), PNG images in `NAME_Images/`, TUM files and `NAME.landmarks.txt`.
 *
 *  1. The constructor creates DIR and NAME_Images/ (removing the images of an earlier run whose
 *     names start with one of `image_labels`) and opens `NAME.rawlog.tmp`.
 *  2. writeImage() and writeFrame() or writeObservation() as the run goes.
 *  3. commit() writes the text files atomically and renames the rawlog into place last, so an
 *     interrupted run never leaves a rawlog that looks complete; destruction without commit()
 *     removes the temporary rawlog. */
class DatasetWriter {
  public:
    DatasetWriter(const std::string& out_prefix, bool with_images,
                  const std::vector<std::string>& image_labels,
                  TPngCoding image_coding = TPngCoding::Default);
    ~DatasetWriter();
    DatasetWriter(const DatasetWriter&) = delete;
    DatasetWriter& operator=(const DatasetWriter&) = delete;

    /// Name of an image relative to the images directory: `LABEL_000123<suffix>.png`.
    static std::string imageFileName(const std::string& label, int frame,
                                     const std::string& suffix = {});
    /// Directory of the images (`DIR/NAME_Images`).
    const std::string& imagesDirectory() const { return m_images_dir; }

    /// Saves an image as PNG in the images directory under `file_name` (written, then renamed).
    void writeImage(const mrpt::img::CImage& image, const std::string& file_name);
    /// Saves an image as PNG beside the rawlog, as `NAME.<suffix>.png` (written, then renamed).
    void writeImageBesideRawlog(const mrpt::img::CImage& image, const std::string& suffix);
    /// Appends one action collection and its sensory frame to the rawlog (format #1).
    void writeFrame(const mrpt::obs::CActionCollection& actions,
                    const mrpt::obs::CSensoryFrame& frame);
    /// Appends one observation to the rawlog (observation-only format).
    void writeObservation(const mrpt::obs::CObservation& observation);
    /// Writes the TUM files (`NAME.<name>.tum`) and the landmarks, then renames the rawlog into
    /// place. On a failure it removes the files it had written and throws, naming the file.
    void commit(const std::vector<TTumFile>& trajectories, const core::LandmarkFile& landmarks,
                const std::string& landmarks_comment = {});

  private:
    static void writePng(const mrpt::img::CImage& image, const std::string& file,
                         TPngCoding coding);

    std::string m_prefix, m_rawlog, m_rawlog_tmp, m_images_dir;
    TPngCoding m_image_coding;
    std::unique_ptr<mrpt::io::CFileGZOutputStream> m_rawlog_out;
    bool m_committed = false;
};

}  // namespace mrpt_vslam::sim
