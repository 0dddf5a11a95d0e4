#include <mrpt_vslam/core/ImageFile.h>
#include <zlib.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace mrpt_vslam::core {

namespace {

uint8_t byteAt(std::string_view b, size_t i) { return static_cast<uint8_t>(b[i]); }

/// Big-endian unsigned integer of `n` bytes at `i`.
uint64_t bigEndian(std::string_view b, size_t i, size_t n)
{
    uint64_t v = 0;
    for (size_t k = 0; k < n; k++) v = (v << 8) | byteAt(b, i + k);
    return v;
}

/// PNG: signature, then chunks (length, type, data, CRC of type and data) up to IEND.
std::string pngDamage(std::string_view b)
{
    for (size_t pos = 8; pos + 8 <= b.size();) {
        const uint64_t length = bigEndian(b, pos, 4), end = pos + 12 + length;
        if (end > b.size()) return "truncated (a PNG whose last chunk is cut short)";
        const auto* typeAndData = reinterpret_cast<const Bytef*>(b.data() + pos + 4);
        if (crc32(crc32(0, nullptr, 0), typeAndData, static_cast<uInt>(4 + length)) !=
            bigEndian(b, end - 4, 4))
            return "corrupt (a PNG whose " + std::string(b.substr(pos + 4, 4)) +
                   " chunk fails its CRC)";
        if (b.substr(pos + 4, 4) == "IEND") return "";
        pos = end;
    }
    return "truncated (a PNG without its IEND chunk)";
}

/// JPEG: markers from SOI on; each scan's entropy-coded data runs to the next marker that is
/// not a stuffed 0xFF00 or a restart marker; complete once EOI is reached.
std::string jpegDamage(std::string_view b)
{
    constexpr uint8_t kEOI = 0xD9, kSOS = 0xDA, kTEM = 0x01;
    const auto isRestart = [](uint8_t m) { return m >= 0xD0 && m <= 0xD7; };
    size_t pos = 2;
    while (pos < b.size()) {
        if (byteAt(b, pos) != 0xFF) {  // stray bytes before a marker, passed over as libjpeg does
            pos++;
            continue;
        }
        while (pos < b.size() && byteAt(b, pos) == 0xFF) pos++;  // fill bytes
        if (pos >= b.size()) break;
        const uint8_t marker = byteAt(b, pos++);
        if (marker == kEOI) return "";
        if (marker == 0x00 || marker == kTEM || isRestart(marker)) continue;  // no segment
        if (pos + 2 > b.size()) break;
        pos += bigEndian(b, pos, 2);
        if (pos > b.size()) return "truncated (a JPEG whose last segment is cut short)";
        if (marker != kSOS) continue;
        while (pos + 1 < b.size() && !(byteAt(b, pos) == 0xFF && byteAt(b, pos + 1) != 0x00 &&
                                       !isRestart(byteAt(b, pos + 1))))
            pos++;
    }
    return "truncated (a JPEG without its end-of-image marker)";
}

}  // namespace

std::string imageFileDamage(std::string_view bytes)
{
    if (bytes.substr(0, 8) == std::string_view("\x89PNG\r\n\x1a\n", 8)) return pngDamage(bytes);
    if (bytes.size() >= 3 && byteAt(bytes, 0) == 0xFF && byteAt(bytes, 1) == 0xD8 &&
        byteAt(bytes, 2) == 0xFF)
        return jpegDamage(bytes);
    return "";
}

void requireIntactImageFile(const mrpt::img::CImage& image, std::string_view what)
{
    if (!image.isExternallyStored()) return;
    std::ifstream in(image.getExternalStorageFileAbsolutePath(), std::ios::binary);
    if (!in) return;  // a missing file is the loader's to report
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const std::string damage = imageFileDamage(bytes);
    if (!damage.empty()) throw std::runtime_error(std::string(what) + "'s file is " + damage);
}

}  // namespace mrpt_vslam::core
