#include "StereoFrontEndApp.h"

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/string_utils.h>
#include <mrpt_vslam/core/AtomicFile.h>
#include <mrpt_vslam/core/EndsWith.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/ObservationSelector.h>
#include <mrpt_vslam/core/OutputDirectory.h>
#include <mrpt_vslam/core/ProgressReporter.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/core/UsageError.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace mrpt_vslam::multirobot {
namespace {

const char* const kSection = "StereoFrontEnd";

/** `DIR/NAME.rawlog.tmp`, renamed to `DIR/NAME.rawlog` by commit(); removed if never
 *  committed. MRPT's gzip stream writes MTIME = 0, so equal content gives equal bytes. */
class TemporaryRawlog {
  public:
    explicit TemporaryRawlog(const std::string& file) : m_file(file), m_tmp(file + ".tmp")
    {
        if (!m_out.open(m_tmp, 9)) throw std::runtime_error(m_tmp + ": cannot create file");
    }
    ~TemporaryRawlog()
    {
        if (m_committed) return;
        m_out.close();
        std::remove(m_tmp.c_str());
    }
    TemporaryRawlog(const TemporaryRawlog&) = delete;
    TemporaryRawlog& operator=(const TemporaryRawlog&) = delete;

    void write(const mrpt::serialization::CSerializable& obj)
    {
        auto ar = mrpt::serialization::archiveFrom(m_out);
        ar << obj;
    }
    void commit()
    {
        m_out.close();
        core::AtomicFile::commitRename(m_tmp, m_file);
        m_committed = true;
    }

  private:
    std::string m_file, m_tmp;
    mrpt::io::CFileGZOutputStream m_out;
    bool m_committed = false;
};

/// The input's name without a `.rawlog` extension: ground truth files start with it.
std::string inputPrefix(const std::string& input)
{
    const std::string ext = ".rawlog";
    if (input.size() > ext.size() &&
        mrpt::system::strCmpI(input.substr(input.size() - ext.size()), ext))
        return input.substr(0, input.size() - ext.size());
    return input;
}

/** The suffixes of the ground-truth files beside `PREFIX.rawlog` (`PREFIX.groundtruth*.tum`,
 *  `PREFIX.odometry*.tum`, `PREFIX.landmarks.txt`), sorted. */
std::vector<std::string> groundTruthSuffixes(const fs::path& prefix)
{
    const std::string stem = prefix.filename().string();
    const fs::path dir = prefix.parent_path().empty() ? fs::path(".") : prefix.parent_path();
    std::vector<std::string> suffixes;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (!entry.is_regular_file() || name.rfind(stem + ".", 0) != 0) continue;
        const std::string suffix = name.substr(stem.size());
        const bool tum = core::endsWith(suffix, ".tum") && (suffix.rfind(".groundtruth", 0) == 0 ||
                                                            suffix.rfind(".odometry", 0) == 0);
        if (tum || suffix == ".landmarks.txt") suffixes.push_back(suffix);
    }
    std::sort(suffixes.begin(), suffixes.end());
    return suffixes;
}
}  // namespace

StereoFrontEndApp::StereoFrontEndApp(TFrontEndCommandLine args) : m_args(std::move(args)) {}

void StereoFrontEndApp::initialize()
{
    m_config.loadFile(m_args.config_file);
    try {
        m_options.loadFromConfigFile(m_config, kSection);
    } catch (const std::invalid_argument& e) {
        throw core::UsageError(m_config.name() + ": " + e.what());
    }
    // The file is shared with the SLAM app: only [StereoFrontEnd] is ours to check.
    std::vector<std::string> sections, keys;
    m_config.getAllSections(sections);
    for (const std::string& section : sections) {
        if (mrpt::system::strCmpI(section, kSection)) continue;
        m_config.getAllKeys(section, keys);
        for (const std::string& key : keys) m_config.read_string(section, key, "");
    }
    m_config.throwIfUnreadKeys();

    if (fs::weakly_canonical(m_args.input) == fs::weakly_canonical(m_args.out_prefix + ".rawlog"))
        throw core::UsageError("--out " + m_args.out_prefix + " would overwrite the input " +
                               m_args.input);
}

mrpt::obs::CObservation::Ptr StereoFrontEndApp::convert(const mrpt::obs::CObservation::Ptr& obs,
                                                        size_t entry_index)
{
    const auto stereo = std::dynamic_pointer_cast<mrpt::obs::CObservationStereoImages>(obs);
    if (!stereo) {
        m_summary.other_entries++;
        return obs;
    }
    StereoFrontEnd& front_end =
        m_front_ends.try_emplace(stereo->sensorLabel, m_options).first->second;
    mrpt::obs::CObservation::Ptr landmarks;
    try {
        m_timer.startStep();
        landmarks = front_end.process(*stereo);
        m_timer.endStep();
    } catch (const std::exception& e) {
        const std::string images =
            core::RawlogReader::describeExternalImages(*stereo, m_args.input);
        throw std::runtime_error(m_args.input + ": entry " + std::to_string(entry_index + 1) +
                                 ", " + core::ObservationSelector::nameOf(*stereo) +
                                 (images.empty() ? "" : " (" + images + ")") + ": " +
                                 core::oneLineMessage(e));
    }
    m_summary.counts += front_end.lastFrameStats();
    return landmarks;
}

void StereoFrontEndApp::removeEarlierOutputs() const
{
    std::error_code ec;
    fs::remove(m_args.out_prefix + ".rawlog", ec);
    for (const std::string& suffix : groundTruthSuffixes(m_args.out_prefix))
        fs::remove(m_args.out_prefix + suffix, ec);
}

void StereoFrontEndApp::copyGroundTruth()
{
    const fs::path prefix(inputPrefix(m_args.input));
    for (const std::string& suffix : groundTruthSuffixes(prefix)) {
        const std::string src = prefix.string() + suffix, dst = m_args.out_prefix + suffix;
        std::error_code ec;
        fs::copy_file(src, dst + ".tmp", fs::copy_options::overwrite_existing, ec);
        if (ec) throw std::runtime_error(dst + ".tmp: cannot copy " + src + ": " + ec.message());
        core::AtomicFile::commitRename(dst + ".tmp", dst);
        m_summary.ground_truth_files.push_back(dst);
    }
}

void StereoFrontEndApp::run()
{
    core::RawlogReader reader(m_args.input);
    const fs::path out_dir = fs::path(m_args.out_prefix).parent_path();
    if (!out_dir.empty()) core::OutputDirectory make_dir(out_dir.string());
    removeEarlierOutputs();  // a failure leaves none of them standing as if this run's
    TemporaryRawlog out(m_args.out_prefix + ".rawlog");
    core::ProgressReporter progress("stereo-frontend", 0, m_args.quiet);

    for (core::TRawlogEntry e; reader.next(e);) {
        const size_t frames_before = m_summary.counts.frames;
        if (e.observation) {
            out.write(*convert(e.observation, e.index));
        } else if (e.actions || e.observations) {
            if (e.actions) {
                out.write(*e.actions);
                m_summary.other_entries++;
            }
            if (e.observations) {
                for (auto& obs : *e.observations) obs = convert(obs, e.index);
                out.write(*e.observations);
            }
        } else {
            out.write(*e.other);
            m_summary.other_entries++;
        }
        if (m_summary.counts.frames != frames_before) progress.update(m_summary.counts.frames);
    }
    if (m_summary.counts.frames == 0)
        throw std::runtime_error(m_args.input +
                                 ": found no CObservationStereoImages; "
                                 "the rawlog has: " +
                                 reader.summary().describe());
    if (m_summary.counts.emitted == 0)
        throw std::runtime_error(
            m_args.input + ": no landmarks in " + std::to_string(m_summary.counts.frames) +
            " stereo pairs: " + StereoFrontEnd::whyNoLandmarks(m_summary.counts, m_options));
    progress.finish(m_summary.counts.frames);
    m_summary.ms_per_frame = m_timer.stepStatistics().mean_ms;
    copyGroundTruth();
    out.commit();
    if (!m_args.quiet) std::cerr << summaryLine() << "\n";
}

std::string StereoFrontEndApp::summaryLine() const
{
    const auto& s = m_summary;
    std::ostringstream line;
    line.setf(std::ios::fixed);
    line.precision(1);
    line << "stereo-frontend: wrote " << m_args.out_prefix << ".rawlog: " << s.counts.frames
         << " stereo frames (";
    for (auto it = m_front_ends.begin(); it != m_front_ends.end(); ++it)
        line << (it == m_front_ends.begin() ? "" : ", ") << it->first;
    line << "), ";
    if (s.counts.rectified > 0)
        line << s.counts.rectified << " of them rectified from their calibration, ";
    line << double(s.counts.points) / s.counts.frames << " points/frame, "
         << double(s.counts.emitted) / s.counts.frames << " landmarks/frame, " << s.ms_per_frame
         << " ms/frame; " << s.other_entries << " other observations copied, "
         << s.ground_truth_files.size() << " ground-truth files copied";
    return line.str();
}

}  // namespace mrpt_vslam::multirobot
