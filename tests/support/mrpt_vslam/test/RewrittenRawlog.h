#pragma once

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/RawlogReader.h>

#include <functional>
#include <string>

namespace mrpt_vslam::test {

/** A format-#1 rawlog `source` rewritten as a user's own might be: external images referred
 *  to by absolute path, only the observations `keep` accepts (all when empty), every sensor
 *  label emptied with `clear_labels`; in format #1 (the source's own actions) or, with
 *  `observations_only`, format #2 (unlabelled `CObservationOdometry` readings integrated from
 *  those actions, stamped with each frame's first observation). */
inline void rewriteRawlog(const std::string& source, const std::string& rawlog,
                          bool observations_only, bool clear_labels,
                          const std::function<bool(const mrpt::obs::CObservation&)>& keep = {})
{
    mrpt::io::CFileGZOutputStream f(rawlog);
    auto ar = mrpt::serialization::archiveFrom(f);
    core::RawlogReader reader(source);
    mrpt::poses::CPose2D odometry;
    for (core::TRawlogEntry e; reader.next(e);) {
        if (!e.actions || !e.observations) continue;
        mrpt::obs::CSensoryFrame frame;
        for (const auto& obs : *e.observations) {
            if (keep && !keep(*obs)) continue;
            if (clear_labels) obs->sensorLabel.clear();
            if (const auto img = std::dynamic_pointer_cast<mrpt::obs::CObservationImage>(obs))
                img->image.setExternalStorage(img->image.getExternalStorageFileAbsolutePath());
            frame.insert(obs);
        }
        if (!observations_only) {
            ar << *e.actions << frame;
            continue;
        }
        odometry = odometry + e.actions->getBestMovementEstimation()->poseChange->getMeanVal();
        mrpt::obs::CObservationOdometry odo;
        odo.timestamp = (*frame.begin())->timestamp;
        odo.odometry = odometry;
        ar << odo;
        for (const auto& obs : frame) ar << *obs;
    }
}

}  // namespace mrpt_vslam::test
