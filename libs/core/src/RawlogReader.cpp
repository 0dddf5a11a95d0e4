#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/filesystem.h>
#include <mrpt/system/string_utils.h>
#include <mrpt_vslam/core/RawlogReader.h>

#include <deque>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace mrpt_vslam::core {

using mrpt::obs::CActionCollection;
using mrpt::obs::CObservation;
using mrpt::obs::CSensoryFrame;
using mrpt::serialization::CSerializable;

namespace {

std::string shortClassName(const CSerializable& obj)
{
    std::string name = obj.GetRuntimeClass()->className;
    const std::string prefix = "mrpt::obs::";
    if (name.rfind(prefix, 0) == 0) name.erase(0, prefix.size());
    return name;
}

/** The innermost "Message:" of an MRPT exception text, without the stream description. */
std::string innermostMessage(const std::string& what)
{
    const auto at = what.rfind("Message:");
    std::string msg = at == std::string::npos ? what : what.substr(at + 8);
    msg = msg.substr(0, msg.find('\n'));
    const auto stream_desc = msg.find(" in mrpt::io::");
    if (stream_desc != std::string::npos) msg.erase(stream_desc);
    return mrpt::system::trim(msg);
}

/** gzip files end with the uncompressed size modulo 2^32 (RFC 1952, ISIZE). */
struct TGzipTrailer {
    bool isGzip = false;
    uint32_t uncompressedSize = 0;
};

TGzipTrailer readGzipTrailer(const std::string& file)
{
    TGzipTrailer t;
    std::ifstream in(file, std::ios::binary);
    unsigned char magic[2] = {0, 0};
    if (!in.read(reinterpret_cast<char*>(magic), 2) || magic[0] != 0x1f || magic[1] != 0x8b)
        return t;
    t.isGzip = true;
    unsigned char isize[4] = {0, 0, 0, 0};
    in.seekg(-4, std::ios::end);
    in.read(reinterpret_cast<char*>(isize), 4);
    t.uncompressedSize = uint32_t(isize[0]) | uint32_t(isize[1]) << 8 | uint32_t(isize[2]) << 16 |
                         uint32_t(isize[3]) << 24;
    return t;
}

}  // namespace

struct RawlogReader::Impl {
    mrpt::io::CFileGZInputStream in;
    mrpt::serialization::CArchiveStreamBase<mrpt::io::CFileGZInputStream> archive{in};
    std::deque<CSerializable::Ptr> pending;  ///< contents of a CRawlog object, or a lookahead
    TGzipTrailer trailer;
    bool ended = false;
};

RawlogReader::RawlogReader(const std::string& file) : m_impl(std::make_unique<Impl>()), m_file(file)
{
    std::string error;
    if (!mrpt::system::fileExists(file) || mrpt::system::directoryExists(file) ||
        !m_impl->in.open(file, error))
        throw std::runtime_error(file + ": cannot open rawlog" +
                                 (error.empty() ? "" : ": " + error));
    m_impl->trailer = readGzipTrailer(file);
    mrpt::img::CImage::setImagesPathBase(imagesDirectory(file));
}

std::string RawlogReader::imagesDirectory(const std::string& file)
{
    const std::filesystem::path rawlog(file);
    const std::filesystem::path dir = rawlog.parent_path();
    const std::string stem = rawlog.stem().string();
    for (const char* suffix : {"_Images", "_images", "_IMAGES"}) {
        const auto candidate = dir / (stem + suffix);
        if (std::filesystem::is_directory(candidate)) return candidate.string();
    }
    return (dir / "Images").string();
}

RawlogReader::~RawlogReader() = default;

void RawlogReader::fail(const std::string& what) const
{
    throw std::runtime_error(m_file + ": " + what);
}

CSerializable::Ptr RawlogReader::readFromFile()
{
    if (m_impl->ended) return nullptr;
    const size_t n = m_summary.objects;
    const std::string after = "corrupt or truncated rawlog after entry " + std::to_string(n) + ": ";
    const uint64_t start = m_impl->in.getPosition();
    CSerializable::Ptr obj;
    try {
        obj = m_impl->archive.ReadObject();
    } catch (const std::exception& e) {
        const std::string reason = innermostMessage(e.what());
        const auto registered = reason.find("' which is not registered");
        const auto name_start = reason.find('\'');
        if (registered != std::string::npos && name_start < registered)
            fail("entry " + std::to_string(n + 1) + " has class '" +
                 reason.substr(name_start + 1, registered - name_start - 1) +
                 "', which is not registered (load the library that defines it)");
        const bool nothing_read = dynamic_cast<const mrpt::serialization::CExceptionEOF*>(&e) &&
                                  m_impl->in.getPosition() == start && m_impl->in.checkEOF();
        if (!nothing_read) fail(after + reason);
        // End of the data: complete only if the gzip trailer agrees on the size.
        if (m_impl->trailer.isGzip &&
            m_impl->trailer.uncompressedSize != static_cast<uint32_t>(start))
            fail(after + "the compressed data ends early");
        m_impl->ended = true;
        return nullptr;
    }
    if (!obj) fail(after + "a null object is stored");
    ++m_summary.objects;
    if (const auto rawlog = std::dynamic_pointer_cast<mrpt::obs::CRawlog>(obj)) {
        for (size_t i = 0; i < rawlog->size(); ++i)
            m_impl->pending.push_back(rawlog->getAsGeneric(i));
        return nextObject();
    }
    return obj;
}

CSerializable::Ptr RawlogReader::nextObject()
{
    if (m_impl->pending.empty()) return readFromFile();
    auto obj = m_impl->pending.front();
    m_impl->pending.pop_front();
    return obj;
}

bool RawlogReader::next(TRawlogEntry& entry)
{
    auto obj = nextObject();
    if (!obj) return false;
    entry = TRawlogEntry();
    entry.index = m_entries++;
    if (auto acts = std::dynamic_pointer_cast<CActionCollection>(obj)) {
        entry.actions = acts;
        auto following = nextObject();
        entry.observations = std::dynamic_pointer_cast<CSensoryFrame>(following);
        if (following && !entry.observations) m_impl->pending.push_front(following);
    } else if (auto sf = std::dynamic_pointer_cast<CSensoryFrame>(obj)) {
        entry.observations = sf;
    } else if (auto o = std::dynamic_pointer_cast<CObservation>(obj)) {
        entry.observation = o;
    } else {
        entry.other = obj;
    }

    if (entry.observation) entry.timestamp = entry.observation->timestamp;
    if (entry.observations && entry.observations->size() > 0)
        entry.timestamp = (*entry.observations->begin())->timestamp;
    else if (entry.actions && entry.actions->size() > 0)
        entry.timestamp = entry.actions->get(0)->timestamp;

    const std::initializer_list<const CSerializable*> parts = {
        entry.actions.get(), entry.observations.get(), entry.observation.get(), entry.other.get()};
    for (const CSerializable* part : parts)
        if (part) account(*part);
    return true;
}

void RawlogReader::account(const CSerializable& obj)
{
    auto& counts = m_summary.byClassAndLabel;
    if (const auto* acts = dynamic_cast<const CActionCollection*>(&obj)) {
        ++m_summary.actionCollections;
        for (size_t i = 0; i < acts->size(); ++i) ++counts[{shortClassName(acts->get(i)), ""}];
    } else if (const auto* sf = dynamic_cast<const CSensoryFrame*>(&obj)) {
        ++m_summary.sensoryFrames;
        for (const auto& o : *sf) ++counts[{shortClassName(*o), o->sensorLabel}];
    } else if (const auto* o = dynamic_cast<const CObservation*>(&obj)) {
        ++m_summary.observations;
        ++counts[{shortClassName(*o), o->sensorLabel}];
    } else {
        ++m_summary.others;
        ++counts[{shortClassName(obj), ""}];
    }
}

TRawlogSummary RawlogReader::summarize(const std::string& file)
{
    RawlogReader reader(file);
    for (TRawlogEntry e; reader.next(e);) {
    }
    return reader.summary();
}

RawlogFormat TRawlogSummary::format() const
{
    const bool pairs = actionCollections + sensoryFrames > 0;
    const bool single = observations > 0;
    if (pairs && single) return RawlogFormat::Mixed;
    if (pairs) return RawlogFormat::ActionObservationPairs;
    return single ? RawlogFormat::ObservationsOnly : RawlogFormat::Empty;
}

size_t TRawlogSummary::count(const std::string& class_name, const std::string& label) const
{
    size_t n = 0;
    for (const auto& [key, c] : byClassAndLabel)
        if (key.first == class_name && (label == "*" || key.second == label)) n += c;
    return n;
}

std::string TRawlogSummary::describe() const
{
    std::string text;
    for (const auto& [key, n] : byClassAndLabel) {
        if (!text.empty()) text += ", ";
        text += std::to_string(n) + " x " + key.first;
        if (!key.second.empty()) text += " (" + key.second + ")";
    }
    return text.empty() ? "nothing" : text;
}

}  // namespace mrpt_vslam::core
