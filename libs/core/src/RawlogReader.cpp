#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/filesystem.h>
#include <mrpt/system/string_utils.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <new>
#include <regex>
#include <stdexcept>

// A sanitizer's report ends the process through its death callback (a fuzzer's, say)
#if defined(__SANITIZE_ADDRESS__)
#define MRPT_VSLAM_SANITIZER
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define MRPT_VSLAM_SANITIZER
#endif
#endif
#if defined(MRPT_VSLAM_SANITIZER)
#include <sanitizer/common_interface_defs.h>
#endif

namespace mrpt_vslam::core {

using mrpt::obs::CActionCollection;
using mrpt::obs::CObservation;
using mrpt::obs::CSensoryFrame;
using mrpt::serialization::CSerializable;

namespace {

/** What a corrupt length beyond RawlogReader::validate()'s memory bound is reported as. */
constexpr const char* kObjectTooLarge =
    "an object asks for more memory than a rawlog of this size can hold";

/** The start of every message about corrupt data found after \a entries good entries. */
std::string corruptAfter(size_t entries)
{
    return "corrupt or truncated rawlog after entry " + std::to_string(entries) + ": ";
}

/** The innermost "Message:" of an MRPT exception text, without the stream description. */
std::string innermostMessage(const std::string& what)
{
    const auto at = what.rfind("Message:");
    std::string msg = at == std::string::npos ? what : what.substr(at + 8);
    msg = msg.substr(0, msg.find('\n'));
    const auto stream_desc = msg.find(" in mrpt::io::");
    if (stream_desc != std::string::npos) msg.erase(stream_desc);
    // bytes of the corrupt data quoted by MRPT stay out of the one-line message
    for (char& c : msg)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
    if (msg.size() > 200) msg = msg.substr(0, 200) + "...";
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

/** The most memory one entry of `file` may ask for: 512 MiB, or more for a rawlog that may be
 *  stored as a single CRawlog object: four times its content (the gzip trailer's size, or 16
 *  times the compressed size, whichever is larger). A corrupt length field beyond it fails at
 *  once instead of filling gigabytes first. */
uint64_t entryMemoryBound(const std::string& file)
{
    std::error_code ec;
    const uint64_t on_disk = std::filesystem::file_size(file, ec);
    const TGzipTrailer gz = readGzipTrailer(file);
    const uint64_t content = ec          ? 0
                             : gz.isGzip ? std::max<uint64_t>(16 * on_disk, gz.uncompressedSize)
                                         : on_disk;
    return (uint64_t{512} << 20) + 4 * content;
}

/** Bounds this process's address space to what it maps now plus `extra` bytes: relative to the
 *  mapping, so that it holds under AddressSanitizer (which reserves terabytes) too. */
void boundAddressSpace(uint64_t extra)
{
    uint64_t mapped_pages = 0;
    std::ifstream("/proc/self/statm") >> mapped_pages;
    const auto page = static_cast<uint64_t>(sysconf(_SC_PAGESIZE));
    const rlim_t bound = mapped_pages * page + extra;
    const rlimit limit{bound, bound};
    setrlimit(RLIMIT_AS, &limit);
}

}  // namespace

struct RawlogReader::Impl {
    mrpt::io::CFileGZInputStream in;
    mrpt::serialization::CArchiveStreamBase<mrpt::io::CFileGZInputStream> archive{in};
    std::deque<CSerializable::Ptr> pending;  ///< contents of a CRawlog object, or a lookahead
    TGzipTrailer trailer;
    bool ended = false;
    uint64_t* progress = nullptr;  ///< validate(): objects read so far, seen by the parent
};

RawlogReader::RawlogReader(const std::string& file) : RawlogReader(file, TUnchecked())
{
    validate(file);
}

RawlogReader::RawlogReader(const std::string& file, TUnchecked)
    : m_impl(std::make_unique<Impl>()), m_file(file)
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

namespace {
/// The images of `images` stored as files, as `'<path>', ...`, then, when some are missing,
/// which and where external images are looked for.
std::string describeImageFiles(std::initializer_list<const mrpt::img::CImage*> images,
                               const std::string& file)
{
    std::string listed, missing;
    for (const auto* image : images) {
        if (!image->isExternallyStored()) continue;
        const std::string path = image->getExternalStorageFileAbsolutePath();
        listed += (listed.empty() ? "'" : ", '") + path + "'";
        if (!std::filesystem::exists(path)) missing += (missing.empty() ? "'" : ", '") + path + "'";
    }
    if (missing.empty()) return listed;
    const std::filesystem::path rawlog(file);
    return listed + " (no such file: " + (missing == listed ? "" : missing + "; ") +
           "the external images of " + rawlog.filename().string() + " are read from the folder " +
           rawlog.stem().string() + "_Images beside it, else from Images)";
}
}  // namespace

std::string RawlogReader::describeExternalImage(const mrpt::img::CImage& image,
                                                const std::string& file)
{
    return describeImageFiles({&image}, file);
}

std::string RawlogReader::describeExternalImages(const mrpt::obs::CObservationStereoImages& stereo,
                                                 const std::string& file)
{
    const std::string images = describeImageFiles({&stereo.imageLeft, &stereo.imageRight}, file);
    return images.empty() ? "" : "images " + images;
}

RawlogReader::~RawlogReader() = default;

void RawlogReader::validate(const std::string& file)
{
    constexpr int kReadError = 3;          ///< the child's status when reading threw
    constexpr unsigned kMaxSeconds = 600;  ///< the longest a rawlog may take to read
    struct TShared {
        uint64_t objects = 0;
        char message[2048] = {};
    };
    void* memory =
        mmap(nullptr, sizeof(TShared), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (memory == MAP_FAILED) throw std::runtime_error(file + ": cannot validate the rawlog");
    auto* shared = new (memory) TShared();
    const uint64_t memory_bound = entryMemoryBound(file);
    std::fflush(nullptr);  // the child must not write the parent's buffered output again
    const pid_t child = fork();
    if (child == 0) {
        // the default action for the signals of a crash or a limit, whatever handlers the
        // program (or a sanitizer, or a fuzzer) installed: the child just ends, the parent reports
        for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGALRM, SIGXCPU})
            std::signal(sig, SIG_DFL);
#if defined(MRPT_VSLAM_SANITIZER)
        __sanitizer_set_death_callback(nullptr);
#endif
        boundAddressSpace(memory_bound);
        const rlimit cpu_limit{kMaxSeconds, kMaxSeconds};
        setrlimit(RLIMIT_CPU, &cpu_limit);
        alarm(kMaxSeconds);  // wall clock too: a read that waits (a FIFO, a stalled disk)
        int status = 0;
        try {
            RawlogReader reader(file, TUnchecked());
            reader.m_impl->progress = &shared->objects;
            for (TRawlogEntry e; reader.next(e);) {
            }
        } catch (const std::bad_alloc&) {
            std::snprintf(shared->message, sizeof(shared->message), "%s: %s%s (%llu MiB)",
                          file.c_str(), corruptAfter(shared->objects).c_str(), kObjectTooLarge,
                          static_cast<unsigned long long>(memory_bound >> 20));
            status = kReadError;
        } catch (const std::exception& e) {
            std::snprintf(shared->message, sizeof(shared->message), "%s", e.what());
            status = kReadError;
        }
        _exit(status);
    }
    int status = 0;
    if (child > 0)
        while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
        }
    const TShared result = *shared;
    munmap(memory, sizeof(TShared));
    if (child < 0) throw std::runtime_error(file + ": cannot validate the rawlog (fork failed)");
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
    if (WIFEXITED(status) && WEXITSTATUS(status) == kReadError && result.message[0] != '\0')
        throw std::runtime_error(result.message);
    if (WIFSIGNALED(status) && (WTERMSIG(status) == SIGALRM || WTERMSIG(status) == SIGXCPU))
        throw std::runtime_error(file + ": reading the rawlog took more than " +
                                 std::to_string(kMaxSeconds / 60) + " min (stopped at entry " +
                                 std::to_string(result.objects + 1) + ")");
    // a signal, or a sanitizer's report of one (it exits instead)
    const std::string how = WIFSIGNALED(status)
                                ? strsignal(WTERMSIG(status))
                                : "exit status " + std::to_string(WEXITSTATUS(status));
    throw std::runtime_error(file + ": corrupt rawlog: reading entry " +
                             std::to_string(result.objects + 1) + " crashed (" + how + ")");
}

void RawlogReader::fail(const std::string& what) const
{
    throw std::runtime_error(m_file + ": " + what);
}

CSerializable::Ptr RawlogReader::readFromFile()
{
    if (m_impl->ended) return nullptr;
    const size_t n = m_summary.objects;
    const std::string after = corruptAfter(n);
    const uint64_t start = m_impl->in.getPosition();
    CSerializable::Ptr obj;
    try {
        obj = m_impl->archive.ReadObject();
    } catch (const std::exception& e) {
        const std::string reason = innermostMessage(e.what());
        const auto registered = reason.find("' which is not registered");
        const auto name_start = reason.find('\'');
        if (registered != std::string::npos && name_start < registered) {
            const std::string name = reason.substr(name_start + 1, registered - name_start - 1);
            // a C++ class name, or bytes of a damaged file read as one
            static const std::regex identifier(
                R"([A-Za-z_][A-Za-z0-9_]*(::[A-Za-z_][A-Za-z0-9_]*)*)");
            if (!std::regex_match(name, identifier)) fail(after + "an unreadable class name");
            fail("entry " + std::to_string(n + 1) + " has class '" + name +
                 "', which is not registered (load the library that defines it)");
        }
        const bool nothing_read = dynamic_cast<const mrpt::serialization::CExceptionEOF*>(&e) &&
                                  m_impl->in.getPosition() == start && m_impl->in.checkEOF();
        // a corrupt length beyond validate()'s memory bound
        if (reason.find("bad_alloc") != std::string::npos) fail(after + kObjectTooLarge);
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
    if (m_impl->progress) *m_impl->progress = m_summary.objects;
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
        if (part) m_summary.add(*part);
    return true;
}

RawlogEntrySource::~RawlogEntrySource() = default;

std::string shortClassName(const mrpt::rtti::TRuntimeClassId& cls)
{
    std::string name = cls.className;
    const std::string prefix = "mrpt::obs::";
    if (name.rfind(prefix, 0) == 0) name.erase(0, prefix.size());
    return name;
}

std::string shortClassName(const CSerializable& obj)
{
    return shortClassName(*obj.GetRuntimeClass());
}

void TRawlogSummary::add(const CSerializable& obj)
{
    auto& counts = byClassAndLabel;
    if (const auto* acts = dynamic_cast<const CActionCollection*>(&obj)) {
        ++actionCollections;
        for (size_t i = 0; i < acts->size(); ++i) ++counts[{shortClassName(acts->get(i)), ""}];
    } else if (const auto* sf = dynamic_cast<const CSensoryFrame*>(&obj)) {
        ++sensoryFrames;
        for (const auto& o : *sf) ++counts[{shortClassName(*o), o->sensorLabel}];
    } else if (const auto* o = dynamic_cast<const CObservation*>(&obj)) {
        ++observations;
        ++counts[{shortClassName(*o), o->sensorLabel}];
    } else {
        ++others;
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
