#pragma once

#include <mrpt_vslam/core/RawlogEntrySource.h>

#include <cstddef>
#include <memory>
#include <string>

namespace mrpt::img {
class CImage;
}
namespace mrpt::obs {
class CObservationStereoImages;
}

namespace mrpt_vslam::core {

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
class RawlogReader : public RawlogEntrySource {
  public:
    /// Opens `file` and validate()s it. \throw std::runtime_error as described above
    explicit RawlogReader(const std::string& file);
    ~RawlogReader() override;
    RawlogReader(const RawlogReader&) = delete;
    RawlogReader& operator=(const RawlogReader&) = delete;

    /** Reads the next entry. \return false at the (clean) end of the file. Throws
     *  std::runtime_error as described above. */
    bool next(TRawlogEntry& entry) override;

    /** What was read so far (all of it once next() returned false). */
    const TRawlogSummary& summary() const override { return m_summary; }
    const std::string& file() const override { return m_file; }

    /** MRPT's folder for the external images of `file` (`DIR/NAME.rawlog`): the first existing
     *  of `DIR/NAME_Images`, `DIR/NAME_images`, `DIR/NAME_IMAGES`, else `DIR/Images`.
     *  (`CRawlog::detectImagesDirectory` of MRPT 2.5.8 drops the separator after DIR.) */
    static std::string imagesDirectory(const std::string& file);

    /** For messages: `'<path>'` of an externally stored image of the rawlog `file`, and where
     *  such images are looked for when it is missing; empty for an image stored in the rawlog. */
    static std::string describeExternalImage(const mrpt::img::CImage& image,
                                             const std::string& file);
    /// describeExternalImage() of a stereo pair: `images 'L', 'R'`; empty when both are stored
    /// in the rawlog.
    static std::string describeExternalImages(const mrpt::obs::CObservationStereoImages& stereo,
                                              const std::string& file);

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
    [[noreturn]] void fail(const std::string& what) const;

    struct Impl;
    std::unique_ptr<Impl> m_impl;
    std::string m_file;
    TRawlogSummary m_summary;
    size_t m_entries = 0;
};

}  // namespace mrpt_vslam::core
