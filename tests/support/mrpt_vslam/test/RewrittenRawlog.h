#pragma once

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2DInterpolator.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/RawlogReader.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace mrpt_vslam::test {

/** A format-#1 rawlog `source` rewritten as a user's own might be: external images referred
 *  to by absolute path, only the observations `keep` accepts (all when empty; it may change
 *  those it keeps), every sensor
 *  label emptied with `clear_labels`; in format #1 (the source's own actions) or, with
 *  `observations_only`, format #2 (unlabelled `CObservationOdometry` readings integrated from
 *  those actions, stamped with each frame's first observation; with `odometry_delay_s` > 0,
 *  as from an odometry of its own clock: one reading at the first frame, then one that long
 *  after each frame, interpolated between the frames, `odometry_delay_s` shorter than the
 *  frames' period). */
inline void rewriteRawlog(const std::string& source, const std::string& rawlog,
                          bool observations_only, bool clear_labels,
                          const std::function<bool(mrpt::obs::CObservation&)>& keep = {},
                          double odometry_delay_s = 0)
{
    mrpt::io::CFileGZOutputStream f(rawlog);
    auto ar = mrpt::serialization::archiveFrom(f);
    core::RawlogReader reader(source);
    std::vector<std::pair<mrpt::poses::CPose2D, mrpt::obs::CSensoryFrame>> frames;
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
        frames.emplace_back(odometry, frame);
    }
    mrpt::poses::CPose2DInterpolator path;  // the odometry between the frames
    for (const auto& [pose, frame] : frames) path.insert((*frame.begin())->timestamp, pose);
    const auto delay = std::chrono::microseconds(std::llround(odometry_delay_s * 1e6));
    for (size_t i = 0; i < frames.size(); i++) {
        const auto& [pose, frame] = frames[i];
        const auto t = (*frame.begin())->timestamp;
        mrpt::obs::CObservationOdometry odo;
        odo.timestamp = t;
        odo.odometry = pose;
        if (odometry_delay_s <= 0 || i == 0) ar << odo;
        for (const auto& obs : frame) ar << *obs;
        if (odometry_delay_s <= 0) continue;
        odo.timestamp = t + delay;
        bool inside = false;
        path.interpolate(odo.timestamp, odo.odometry, inside);
        if (!inside) odo.odometry = pose;  // after the last frame: standing
        ar << odo;
    }
}

}  // namespace mrpt_vslam::test
