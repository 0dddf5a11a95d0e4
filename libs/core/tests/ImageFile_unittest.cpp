#include <gtest/gtest.h>
#include <mrpt/img/CImage.h>
#include <mrpt_vslam/core/ImageFile.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <algorithm>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using mrpt_vslam::core::imageFileDamage;
using mrpt_vslam::core::requireIntactImageFile;

namespace {

/// 64 x 48 of uniform noise (its compressed data holds 0xFF bytes), encoded as `ext` says.
std::string encodedNoise(const std::string& ext, const std::vector<int>& params = {})
{
    cv::Mat image(48, 64, CV_8UC1);
    std::mt19937 rng(7);
    for (int r = 0; r < image.rows; r++)
        for (int c = 0; c < image.cols; c++) image.at<uint8_t>(r, c) = rng() & 0xFF;
    std::vector<uint8_t> bytes;
    EXPECT_TRUE(cv::imencode(ext, image, bytes, params));
    return std::string(bytes.begin(), bytes.end());
}

}  // namespace

TEST(ImageFile, EveryProperPrefixOfAPngOrJpegIsTruncatedAndTheWholeFileIsNot)
{
    const std::vector<std::pair<std::string, std::string>> files = {
        {"png", encodedNoise(".png")},
        {"baseline jpeg", encodedNoise(".jpg")},
        {"progressive jpeg", encodedNoise(".jpg", {cv::IMWRITE_JPEG_PROGRESSIVE, 1})},
        {"jpeg with restart markers", encodedNoise(".jpg", {cv::IMWRITE_JPEG_RST_INTERVAL, 2})}};
    for (const auto& [name, bytes] : files) {
        EXPECT_EQ(imageFileDamage(bytes), "") << name;
        // bytes after the end (some cameras append data) do not make a file incomplete
        EXPECT_EQ(imageFileDamage(bytes + std::string(100, '\xFF')), "") << name;
        const size_t signature = name == "png" ? 8 : 3;  // the format is known from there on
        size_t flagged = 0;
        for (size_t n = signature; n < bytes.size(); n++)
            flagged += imageFileDamage(std::string_view(bytes).substr(0, n)).empty() ? 0 : 1;
        EXPECT_EQ(flagged, bytes.size() - signature) << name;
    }
    const std::string png = files[0].second, jpeg = files[1].second;
    EXPECT_EQ(imageFileDamage(png.substr(0, png.size() - 12)),
              "truncated (a PNG without its IEND chunk)");
    EXPECT_EQ(imageFileDamage(png.substr(0, png.size() / 2)),
              "truncated (a PNG whose last chunk is cut short)");
    EXPECT_EQ(imageFileDamage(jpeg.substr(0, jpeg.size() / 2)),
              "truncated (a JPEG without its end-of-image marker)");
    // a PNG whose bytes changed: the chunk that holds them fails its CRC, whichever byte it is
    const size_t idat = png.find("IDAT");
    for (const size_t at : {idat - 1, idat, idat + 4, idat + 100, png.size() - 5}) {
        std::string flipped = png;
        flipped[at] = static_cast<char>(flipped[at] ^ 0x10);
        EXPECT_NE(imageFileDamage(flipped), "") << at;
    }
    std::string flipped = png;
    flipped[idat + 100] = static_cast<char>(flipped[idat + 100] ^ 0x10);
    EXPECT_EQ(imageFileDamage(flipped), "corrupt (a PNG whose IDAT chunk fails its CRC)");
    // other formats, and bytes of no format, are not judged
    EXPECT_EQ(imageFileDamage(encodedNoise(".bmp").substr(0, 100)), "");
    EXPECT_EQ(imageFileDamage("P5\n64 48\n255\n"), "");
    EXPECT_EQ(imageFileDamage(""), "");
}

// Files with bytes overwritten, inserted or removed, and cut short: every one is judged without
// reading outside its bytes (the sanitizer build checks) and with a known verdict.
TEST(ImageFile, CorruptFilesGetAVerdictWithoutReadingPastTheirEnd)
{
    const std::vector<std::string> whole = {
        encodedNoise(".png"), encodedNoise(".jpg"),
        encodedNoise(".jpg", {cv::IMWRITE_JPEG_PROGRESSIVE, 1})};
    const std::vector<std::string> verdicts = {
        "", "truncated (a PNG whose last chunk is cut short)",
        "truncated (a PNG without its IEND chunk)",
        "truncated (a JPEG whose last segment is cut short)",
        "truncated (a JPEG without its end-of-image marker)"};
    const auto known = [&](const std::string& v) {
        return std::find(verdicts.begin(), verdicts.end(), v) != verdicts.end() ||
               (v.rfind("corrupt (a PNG whose ", 0) == 0 &&
                v.size() == std::string("corrupt (a PNG whose ABCD chunk fails its CRC)").size());
    };
    std::mt19937 rng(11);
    size_t judged = 0;
    for (int i = 0; i < 3000; i++) {
        std::string bytes = whole[i % whole.size()];
        for (int edits = 1 + static_cast<int>(rng() % 4); edits > 0; edits--) {
            const size_t at = rng() % bytes.size();
            const char byte = static_cast<char>(rng() & 0xFF);
            switch (rng() % 4) {
                case 0:
                    bytes[at] = byte;
                    break;
                case 1:
                    bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at), byte);
                    break;
                case 2:
                    if (bytes.size() > 16) bytes.erase(at, 1);
                    break;
                default:
                    bytes.resize(std::max<size_t>(at, 16));  // cut short
            }
        }
        // an exact-size copy, so that a read past the end is outside the allocation
        const std::unique_ptr<char[]> copy(new char[bytes.size()]);
        std::copy(bytes.begin(), bytes.end(), copy.get());
        const std::string verdict = imageFileDamage(std::string_view(copy.get(), bytes.size()));
        EXPECT_TRUE(known(verdict)) << verdict;
        judged += verdict.empty() ? 0 : 1;
    }
    EXPECT_GT(judged, 0u);
}

TEST(ImageFile, AnExternalImageWhoseFileIsCutShortIsRefusedNamingIt)
{
    const mrpt_vslam::test::ScratchFolder scratch("ImageFile_unittest");
    const std::string png = encodedNoise(".png");
    const std::string whole = scratch.write("whole.png", png);
    const std::string cut = scratch.write("cut.png", png.substr(0, png.size() - 20));

    mrpt::img::CImage image;
    image.setExternalStorage(whole);
    EXPECT_NO_THROW(requireIntactImageFile(image));
    image.setExternalStorage(cut);
    try {
        requireIntactImageFile(image, "the left image");
        ADD_FAILURE() << "a truncated file passed";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "the left image's file is truncated (a PNG whose last chunk is cut short)");
    }
    // a missing file is left to the loader's error; an image in memory has no file
    image.setExternalStorage(scratch.file("missing.png"));
    EXPECT_NO_THROW(requireIntactImageFile(image));
    EXPECT_NO_THROW(requireIntactImageFile(mrpt::img::CImage(8, 8, mrpt::img::CH_GRAY)));
}
