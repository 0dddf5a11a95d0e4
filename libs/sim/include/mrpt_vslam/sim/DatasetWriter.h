#pragma once

#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/sim/CeilingLights.h>

#include <memory>
#include <string>
#include <vector>

namespace mrpt_vslam::sim {

/** Writes a simulated dataset for `DIR/NAME` (BRIEF §3):
 *  `NAME.rawlog` (format #1: action collection, sensory frame, ...), PNG images in `NAME_Images/`,
 *  `NAME.groundtruth.tum`, `NAME.odometry.tum` and `NAME.landmarks.txt`.
 *
 *  1. The constructor creates DIR and NAME_Images/ (removing images of an earlier run) and opens
 *     `NAME.rawlog.tmp`.
 *  2. writeImage() and writeFrame() once per frame.
 *  3. commit() writes the text files atomically and renames the rawlog into place last, so an
 *     interrupted run never leaves a rawlog that looks complete; destruction without commit()
 *     removes the temporary rawlog. */
class DatasetWriter {
  public:
    DatasetWriter(const std::string& out_prefix, bool with_images);
    ~DatasetWriter();
    DatasetWriter(const DatasetWriter&) = delete;
    DatasetWriter& operator=(const DatasetWriter&) = delete;

    /// Name of the image of a frame, relative to the images directory (`OMNICAM_000123.png`).
    static std::string imageFileName(int frame);
    /// Directory of the images (`DIR/NAME_Images`).
    const std::string& imagesDirectory() const { return m_images_dir; }

    /// Saves a grayscale image as PNG under imageFileName(frame) (written, then renamed).
    void writeImage(const mrpt::img::CImage& image, int frame);
    /// Appends one action collection and its sensory frame to the rawlog.
    void writeFrame(const mrpt::obs::CActionCollection& actions,
                    const mrpt::obs::CSensoryFrame& frame);
    /// Writes ground truth, odometry and landmarks, then renames the rawlog into place.
    void commit(const core::TumTrajectory& ground_truth, const core::TumTrajectory& odometry,
                const std::vector<TCeilingLight>& lights);

  private:
    std::string m_prefix, m_rawlog, m_rawlog_tmp, m_images_dir;
    std::unique_ptr<mrpt::io::CFileGZOutputStream> m_rawlog_out;
    bool m_committed = false;
};

}  // namespace mrpt_vslam::sim
