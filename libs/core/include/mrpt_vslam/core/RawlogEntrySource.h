#pragma once

#include <mrpt/core/Clock.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <cstddef>
#include <map>
#include <string>
#include <utility>

namespace mrpt_vslam::core {

/** How a rawlog stores its data (doc/data-formats.md). */
enum class RawlogFormat {
    Empty,                   ///< no actions or observations (read yet)
    ActionObservationPairs,  ///< #1: CActionCollection, CSensoryFrame, ...
    ObservationsOnly,        ///< #2: one CObservation after another
    Mixed                    ///< both kinds of entries
};

/** One step of a rawlog. Exactly one of the groups is set:
 *  `actions` and/or `observations` (format #1: an action collection with the sensory frame that
 *  follows it; either may be missing at the ends or in odd files), `observation` (format #2),
 *  or `other` (any other serializable object the file holds); or, from a live source only,
 *  none: a time barrier (`time_barrier`). */
struct TRawlogEntry {
    mrpt::obs::CActionCollection::Ptr actions;
    mrpt::obs::CSensoryFrame::Ptr observations;
    mrpt::obs::CObservation::Ptr observation;
    mrpt::serialization::CSerializable::Ptr other;
    /** Time of the observation, of the first observation of the frame, or of the first action;
     *  INVALID_TIMESTAMP if none has one. */
    mrpt::Clock::time_point timestamp = INVALID_TIMESTAMP;
    size_t index = 0;  ///< 0-based number of this entry among those next() returned
    /** No object: the source gives no more entries at or before `timestamp` (a live source
     *  knows it from the robots' watermarks), so the step of that time need not wait for a
     *  later entry. */
    bool time_barrier = false;
};

/// A class as messages name it: classes of `mrpt::obs` without their namespace.
std::string shortClassName(const mrpt::rtti::TRuntimeClassId& cls);
/// The class of `obj` as messages name it (shortClassName() of its class).
std::string shortClassName(const mrpt::serialization::CSerializable& obj);

/** What a rawlog holds, to tell the user what was found when it does not fit the app. */
struct TRawlogSummary {
    size_t objects = 0;            ///< top-level objects read from the file
    size_t actionCollections = 0;  ///< top-level CActionCollection
    size_t sensoryFrames = 0;      ///< top-level CSensoryFrame
    size_t observations = 0;       ///< top-level CObservation (format #2)
    size_t others = 0;             ///< top-level objects of any other class
    /** Count per (class, sensorLabel) of every observation (top-level or inside a frame) and
     *  every action ("" label); classes of `mrpt::obs` without their namespace. */
    std::map<std::pair<std::string, std::string>, size_t> byClassAndLabel;

    /// Counts `obj` (an action collection, a sensory frame, an observation or any other object).
    void add(const mrpt::serialization::CSerializable& obj);
    RawlogFormat format() const;
    /** Observations (or actions) of `class_name` with `label` ("*": any label). */
    size_t count(const std::string& class_name, const std::string& label = "*") const;
    /** e.g. "320 x CObservationOdometry (ODOM), 320 x CObservationImage (OMNICAM)", or
     *  "nothing" for an empty rawlog. */
    std::string describe() const;
};

/** Where a run reads its rawlog entries from, one after another: a rawlog file (RawlogReader)
 *  or readings arriving live (team::TeamListener). */
class RawlogEntrySource {
  public:
    virtual ~RawlogEntrySource();
    /** The next entry. \return false at the end of the data. Throws std::runtime_error naming
     *  file() when the data cannot be read. */
    virtual bool next(TRawlogEntry& entry) = 0;
    /// What was read so far.
    virtual const TRawlogSummary& summary() const = 0;
    /// The rawlog file, or the address the readings arrive at.
    virtual const std::string& file() const = 0;
    /** Called after each filter step: every entry returned before the last one is in a finished
     *  step (the last one opened the next step, unless it was a time barrier). */
    virtual void stepFinished() {}
};

}  // namespace mrpt_vslam::core
