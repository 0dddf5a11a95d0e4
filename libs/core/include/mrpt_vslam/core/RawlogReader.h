#pragma once

#include <mrpt/core/Clock.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <cstddef>
#include <map>
#include <memory>
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
 *  or `other` (any other serializable object the file holds). */
struct TRawlogEntry {
    mrpt::obs::CActionCollection::Ptr actions;
    mrpt::obs::CSensoryFrame::Ptr observations;
    mrpt::obs::CObservation::Ptr observation;
    mrpt::serialization::CSerializable::Ptr other;
    /** Time of the observation, of the first observation of the frame, or of the first action;
     *  INVALID_TIMESTAMP if none has one. */
    mrpt::Clock::time_point timestamp = INVALID_TIMESTAMP;
    size_t index = 0;  ///< 0-based number of this entry among those next() returned
};

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

    RawlogFormat format() const;
    /** Observations (or actions) of `class_name` with `label` ("*": any label). */
    size_t count(const std::string& class_name, const std::string& label = "*") const;
    /** e.g. "320 x CObservationOdometry (ODOM), 320 x CObservationImage (OMNICAM)", or
     *  "nothing" for an empty rawlog. */
    std::string describe() const;
};

/** Reads a rawlog entry by entry, in either format, and fails loudly: every problem is an
 *  exception naming the file, never a silent early end.
 *  - missing file: `"<file>: cannot open rawlog"`;
 *  - not a rawlog, corrupt, truncated: `"<file>: corrupt or truncated rawlog after entry N:
 *    <reason>"` (N objects were read fine);
 *  - an object of a class that is not registered (its plugin library not loaded):
 *    `"<file>: entry N+1 has class 'X', which is not registered ..."`;
 *  - an object whose corrupt content crashes MRPT's own deserialization (e.g. a grid size
 *    from flipped bits): `"<file>: corrupt rawlog: reading entry N+1 crashed (<signal>)"`.
 *  The constructor reads the whole file once in a child process first (validate()), so that
 *  no corrupt file can crash or exhaust the calling program, and every problem above is
 *  reported before the first entry is returned.
 *  A file holding a single CRawlog object is read as the entries it contains. On opening, the
 *  folder of externally stored images is set (`CImage::setImagesPathBase`) to
 *  imagesDirectory().
 *
 *  Usage:
 *  \code
 *  RawlogReader reader(file);
 *  for (TRawlogEntry e; reader.next(e);) { ... }
 *  if (nothing useful) throw ...("found no OMNICAM images; the rawlog has: " +
 *                                reader.summary().describe());
 *  \endcode
 */
class RawlogReader {
  public:
    /// Opens `file` and validate()s it. \throw std::runtime_error as described above
    explicit RawlogReader(const std::string& file);
    ~RawlogReader();
    RawlogReader(const RawlogReader&) = delete;
    RawlogReader& operator=(const RawlogReader&) = delete;

    /** Reads the next entry. \return false at the (clean) end of the file. Throws
     *  std::runtime_error as described above. */
    bool next(TRawlogEntry& entry);

    /** What was read so far (all of it once next() returned false). */
    const TRawlogSummary& summary() const { return m_summary; }
    const std::string& file() const { return m_file; }

    /** MRPT's folder for the external images of `file` (`DIR/NAME.rawlog`): the first existing
     *  of `DIR/NAME_Images`, `DIR/NAME_images`, `DIR/NAME_IMAGES`, else `DIR/Images`.
     *  (`CRawlog::detectImagesDirectory` of MRPT 2.5.8 drops the separator after DIR.) */
    static std::string imagesDirectory(const std::string& file);

    /** Reads a whole rawlog and returns its summary. */
    static TRawlogSummary summarize(const std::string& file);

    /** Reads every object of `file` in a child process (fork) with its memory and time bounded
     *  (512 MiB more than the child maps at the start, or four times the rawlog's content for
     *  large rawlogs; 10 min of CPU and of wall clock), and throws what reading it there threw,
     *  or the crash, naming the entry. Returns if it reads cleanly. */
    static void validate(const std::string& file);

  private:
    struct TUnchecked {};
    RawlogReader(const std::string& file, TUnchecked);
    /** Next object from the file or the pending queue; nullptr at the end. */
    mrpt::serialization::CSerializable::Ptr nextObject();
    mrpt::serialization::CSerializable::Ptr readFromFile();
    void account(const mrpt::serialization::CSerializable& obj);
    [[noreturn]] void fail(const std::string& what) const;

    struct Impl;
    std::unique_ptr<Impl> m_impl;
    std::string m_file;
    TRawlogSummary m_summary;
    size_t m_entries = 0;
};

}  // namespace mrpt_vslam::core
