#pragma once

#include <mrpt/obs/CObservation.h>
#include <mrpt_vslam/core/CheckedConfigFile.h>
#include <mrpt_vslam/core/RunTimer.h>
#include <mrpt_vslam/multirobot/StereoFrontEnd.h>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "FrontEndCommandLine.h"

namespace mrpt_vslam::multirobot {

/** The stereo-frontend app (doc/stereo-frontend.md): reads a rawlog, replaces every
 *  `<ROBOT>_STEREO` CObservationStereoImages with the `<ROBOT>_LANDMARKS`
 *  CObservationVisualLandmarks of that robot's StereoFrontEnd, copies every other entry
 *  unchanged and in order, and writes `DIR/NAME.rawlog` plus copies of the ground-truth files
 *  beside the input.
 *
 *  1. initialize(): reads `[StereoFrontEnd]` (unknown keys there are errors, other sections are
 *     ignored) and checks that the output does not overwrite the input; throws core::UsageError.
 *  2. run(): converts, writing `DIR/NAME.rawlog.tmp`, copies the ground truth, renames the rawlog
 *     into place last; throws std::runtime_error naming the file and entry on bad data, and then
 *     leaves no `DIR/NAME.rawlog`. */
class StereoFrontEndApp {
  public:
    explicit StereoFrontEndApp(TFrontEndCommandLine args);

    void initialize();
    void run();

    /** What run() did. */
    struct TSummary {
        size_t frames = 0;                            ///< stereo frames turned into landmarks
        size_t rectified = 0;                         ///< of those, rectified from the calibration
        StereoFrontEnd::TFrameStats counts;           ///< of all frames, summed
        size_t other_entries = 0;                     ///< entries or observations copied unchanged
        double ms_per_frame = 0;                      ///< mean front-end time per stereo frame
        std::vector<std::string> ground_truth_files;  ///< copied, output names
    };
    const TSummary& summary() const { return m_summary; }

  private:
    /** The entry to write for one observation: the landmarks of a stereo observation (any
     *  label), else `obs` itself. */
    mrpt::obs::CObservation::Ptr convert(const mrpt::obs::CObservation::Ptr& obs,
                                         size_t entry_index);
    /// Removes `OUT.rawlog` and the ground-truth files of an earlier run with the same --out.
    void removeEarlierOutputs() const;
    void copyGroundTruth();
    std::string summaryLine() const;

    TFrontEndCommandLine m_args;
    core::CheckedConfigFile m_config;
    StereoFrontEnd::TOptions m_options;
    std::map<std::string, StereoFrontEnd> m_front_ends;  ///< one per stereo label
    core::RunTimer m_timer;                              ///< one step per stereo frame
    TSummary m_summary;
};

}  // namespace mrpt_vslam::multirobot
