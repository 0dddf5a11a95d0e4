#include <gtest/gtest.h>
#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/test/RunFiles.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

using mrpt_vslam::test::readBytes;

namespace fs = std::filesystem;
using namespace mrpt::obs;
using mrpt_vslam::core::RawlogFormat;
using mrpt_vslam::core::RawlogReader;
using mrpt_vslam::core::TRawlogEntry;

namespace {

/** A folder of this test process, removed at exit. */
struct TScratch {
    fs::path dir =
        fs::path(::testing::TempDir()) / ("RawlogReader_unittest_" + std::to_string(::getpid()));
    TScratch() { fs::create_directories(dir); }
    ~TScratch() { fs::remove_all(dir); }
};

fs::path scratchDir()
{
    static const TScratch scratch;
    return scratch.dir;
}

CObservationOdometry::Ptr odometry(double t)
{
    auto o = CObservationOdometry::Create();
    o->sensorLabel = "ODOM";
    o->timestamp = mrpt::Clock::fromDouble(t);
    o->odometry = mrpt::poses::CPose2D(t, 0, 0);
    return o;
}

CObservationBearingRange::Ptr bearings(double t)
{
    auto o = CObservationBearingRange::Create();
    o->sensorLabel = "OMNICAM_BEARINGS";
    o->timestamp = mrpt::Clock::fromDouble(t);
    return o;
}

/** Format #1: `pairs` (action collection, sensory frame) pairs, stamps 1000, 1001, ... */
std::string writePairs(const std::string& name, int pairs)
{
    const std::string file = (scratchDir() / name).string();
    mrpt::io::CFileGZOutputStream f(file);
    auto ar = mrpt::serialization::archiveFrom(f);
    for (int i = 0; i < pairs; ++i) {
        CActionRobotMovement2D move;
        move.timestamp = mrpt::Clock::fromDouble(1000.0 + i);
        CActionCollection acts;
        acts.insert(move);
        CSensoryFrame sf;
        sf.insert(bearings(1000.0 + i));
        sf.insert(odometry(1000.0 + i));
        ar << acts << sf;
    }
    return file;
}

/** Format #2: four odometry and two bearing observations, stamps 2000..2005. */
std::string writeObservations(const std::string& name)
{
    const std::string file = (scratchDir() / name).string();
    mrpt::io::CFileGZOutputStream f(file);
    auto ar = mrpt::serialization::archiveFrom(f);
    for (int i = 0; i < 6; ++i) {
        if (i % 3 == 2)
            ar << *bearings(2000.0 + i);
        else
            ar << *odometry(2000.0 + i);
    }
    return file;
}

std::string writeBytes(const std::string& name, const std::string& bytes)
{
    const std::string file = (scratchDir() / name).string();
    std::ofstream(file, std::ios::binary) << bytes;
    return file;
}

/** Reads all of `file`; returns the error text ("" if none). */
std::string readAllError(const std::string& file, size_t* entries = nullptr)
{
    try {
        RawlogReader reader(file);
        size_t n = 0;
        for (TRawlogEntry e; reader.next(e);) ++n;
        if (entries) *entries = n;
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return {};
}

}  // namespace

TEST(RawlogReader, ReadsActionObservationPairs)
{
    const std::string file = writePairs("pairs.rawlog", 3);
    RawlogReader reader(file);
    TRawlogEntry e;
    for (int i = 0; i < 3; ++i) {
        ASSERT_TRUE(reader.next(e));
        EXPECT_EQ(e.index, static_cast<size_t>(i));
        ASSERT_TRUE(e.actions);
        ASSERT_TRUE(e.observations);
        EXPECT_FALSE(e.observation);
        EXPECT_EQ(e.actions->size(), 1u);
        EXPECT_EQ(e.observations->size(), 2u);
        EXPECT_DOUBLE_EQ(mrpt::Clock::toDouble(e.timestamp), 1000.0 + i);
    }
    EXPECT_FALSE(reader.next(e));
    EXPECT_FALSE(reader.next(e));  // stays at the end
    const auto& s = reader.summary();
    EXPECT_EQ(s.objects, 6u);
    EXPECT_EQ(s.actionCollections, 3u);
    EXPECT_EQ(s.sensoryFrames, 3u);
    EXPECT_EQ(s.observations, 0u);
    EXPECT_EQ(s.format(), RawlogFormat::ActionObservationPairs);
    EXPECT_EQ(s.count("CObservationOdometry", "ODOM"), 3u);
    EXPECT_EQ(s.count("CObservationOdometry", "OMNICAM"), 0u);
    EXPECT_EQ(s.describe(),
              "3 x CActionRobotMovement2D, 3 x CObservationBearingRange (OMNICAM_BEARINGS), "
              "3 x CObservationOdometry (ODOM)");
}

TEST(RawlogReader, ReadsObservationOnlyRawlogs)
{
    RawlogReader reader(writeObservations("obs.rawlog"));
    TRawlogEntry e;
    size_t n = 0;
    while (reader.next(e)) {
        ASSERT_TRUE(e.observation);
        EXPECT_FALSE(e.actions);
        EXPECT_FALSE(e.observations);
        EXPECT_DOUBLE_EQ(mrpt::Clock::toDouble(e.timestamp), 2000.0 + n);
        ++n;
    }
    EXPECT_EQ(n, 6u);
    const auto& s = reader.summary();
    EXPECT_EQ(s.format(), RawlogFormat::ObservationsOnly);
    EXPECT_EQ(s.objects, 6u);
    EXPECT_EQ(s.count("CObservationOdometry"), 4u);
    EXPECT_EQ(s.count("CObservationBearingRange", "OMNICAM_BEARINGS"), 2u);
    EXPECT_EQ(s.describe(),
              "2 x CObservationBearingRange (OMNICAM_BEARINGS), 4 x CObservationOdometry (ODOM)");
}

TEST(RawlogReader, ReadsASingleCRawlogObject)
{
    CRawlog rawlog;
    rawlog.insert(odometry(1.0));
    rawlog.insert(odometry(2.0));
    const std::string file = (scratchDir() / "crawlog.rawlog").string();
    {
        mrpt::io::CFileGZOutputStream f(file);
        mrpt::serialization::archiveFrom(f) << rawlog;
    }
    const auto s = RawlogReader::summarize(file);
    EXPECT_EQ(s.objects, 1u);
    EXPECT_EQ(s.observations, 2u);
    EXPECT_EQ(s.format(), RawlogFormat::ObservationsOnly);
}

TEST(RawlogReader, EmptyRawlogHasNoEntries)
{
    const std::string file = (scratchDir() / "empty.rawlog").string();
    {
        mrpt::io::CFileGZOutputStream f(file);
    }
    size_t n = 99;
    EXPECT_EQ(readAllError(file, &n), "");
    EXPECT_EQ(n, 0u);
    const auto s = RawlogReader::summarize(file);
    EXPECT_EQ(s.format(), RawlogFormat::Empty);
    EXPECT_EQ(s.describe(), "nothing");
}

TEST(RawlogReader, TruncatedFileIsAnError)
{
    const std::string bytes = readBytes(writeObservations("full.rawlog"));
    ASSERT_GT(bytes.size(), 40u);
    const std::string half = writeBytes("half.rawlog", bytes.substr(0, bytes.size() / 2));
    const std::string msg = readAllError(half);
    EXPECT_EQ(msg.rfind(half + ": corrupt or truncated rawlog after entry ", 0), 0u) << msg;

    // Only the gzip trailer is cut: every object decompresses, the size check catches it.
    const std::string no_trailer =
        writeBytes("no_trailer.rawlog", bytes.substr(0, bytes.size() - 4));
    EXPECT_EQ(
        readAllError(no_trailer),
        no_trailer + ": corrupt or truncated rawlog after entry 6: the compressed data ends early");
}

TEST(RawlogReader, CorruptLengthFailsBeforeAllocating)
{
    // An odometry reading whose label's length field says 1.5 GiB: refused by validate()'s
    // memory bound, not allocated and filled before the read fails.
    const std::string plain = (scratchDir() / "long_label.plain").string();
    {
        auto o = odometry(1.0);
        o->sensorLabel = "LENGTH_FIELD_BEFORE_THIS";
        mrpt::io::CFileOutputStream f(plain);
        mrpt::serialization::archiveFrom(f) << *o;
    }
    std::string bytes = readBytes(plain);
    const auto at = bytes.find("LENGTH_FIELD_BEFORE_THIS");
    ASSERT_NE(at, std::string::npos);
    ASSERT_GE(at, 4u);
    ASSERT_EQ(bytes.substr(at - 4, 4), std::string("\x18\0\0\0", 4));  // uint32 24, LE
    bytes.replace(at - 4, 4, std::string("\0\0\0\x60", 4));            // 0x60000000
    const std::string file = writeBytes("long_label.rawlog", bytes);
#if defined(__SANITIZE_ADDRESS__)
    // AddressSanitizer ends a process whose allocation fails (its operator new never throws)
    EXPECT_EQ(readAllError(file),
              file + ": corrupt rawlog: reading entry 1 crashed (exit status 1)");
#else
    EXPECT_EQ(readAllError(file), file +
                                      ": corrupt or truncated rawlog after entry 0: an object "
                                      "asks for more memory than a rawlog of this size can hold");
#endif
}

TEST(RawlogReader, GarbageFileIsAnError)
{
    const std::string file = writeBytes("garbage.rawlog", "this is not a rawlog at all\n");
    const std::string msg = readAllError(file);
    EXPECT_EQ(msg.rfind(file + ": corrupt or truncated rawlog after entry 0: ", 0), 0u) << msg;
}

TEST(RawlogReader, MissingFileIsAnError)
{
    const std::string file = (scratchDir() / "does_not_exist.rawlog").string();
    EXPECT_EQ(readAllError(file), file + ": cannot open rawlog");
    EXPECT_EQ(readAllError(scratchDir().string()), scratchDir().string() + ": cannot open rawlog");
}

// A class name is named as a plugin's to load; bytes that cannot be a class name (a damaged
// file) are a damaged file
TEST(RawlogReader, UnregisteredClassIsNamed)
{
    const auto withClass = [](const std::string& name) {
        const std::string file = (scratchDir() / "unknown_class.rawlog").string();
        mrpt::io::CFileGZOutputStream f(file);
        auto ar = mrpt::serialization::archiveFrom(f);
        ar << *odometry(1.0);
        // What a plugin class would look like: header with its name, version, end flag.
        ar << static_cast<uint8_t>(0x80 | name.size());
        ar.WriteBuffer(name.data(), name.size());
        ar << static_cast<uint8_t>(0) << static_cast<uint8_t>(0x88);
        return file;
    };
    std::string file = withClass("myplugin::CObservationThing");
    EXPECT_EQ(readAllError(file),
              file +
                  ": entry 2 has class 'myplugin::CObservationThing', which is not registered "
                  "(load the library that defines it)");
    file = withClass("\x8f?8\x01y\xe2");
    EXPECT_EQ(readAllError(file),
              file + ": corrupt or truncated rawlog after entry 1: an unreadable class name");
}

TEST(RawlogReader, ExternalImagesFolderIsDetected)
{
    const std::string file = writeObservations("withimages.rawlog");
    const fs::path images = scratchDir() / "withimages_Images";
    fs::create_directories(images);
    EXPECT_EQ(RawlogReader::imagesDirectory(file), images.string());
    RawlogReader reader(file);
    EXPECT_EQ(mrpt::img::CImage::getImagesPathBase(), images.string());
    EXPECT_EQ(RawlogReader::imagesDirectory((scratchDir() / "other.rawlog").string()),
              (scratchDir() / "Images").string());
}

TEST(RawlogReader, MessagesSayWhereAMissingExternalImageWasLookedFor)
{
    const fs::path images = scratchDir() / "described_Images";
    fs::create_directories(images);
    mrpt::img::CImage::setImagesPathBase(images.string());
    mrpt::img::CImage stored(4, 4, mrpt::img::CH_GRAY);
    EXPECT_EQ(RawlogReader::describeExternalImage(stored, "described.rawlog"), "");
    stored.saveToFile((images / "present.png").string());
    mrpt::img::CImage present, missing;
    present.setExternalStorage("present.png");
    missing.setExternalStorage("missing.png");
    EXPECT_EQ(RawlogReader::describeExternalImage(present, "dir/described.rawlog"),
              "'" + (images / "present.png").string() + "'");
    EXPECT_EQ(RawlogReader::describeExternalImage(missing, "dir/described.rawlog"),
              "'" + (images / "missing.png").string() +
                  "' (no such file: the external images of described.rawlog are read from the "
                  "folder described_Images beside it, else from Images)");
    // a stereo pair names both images and which is missing
    mrpt::obs::CObservationStereoImages stereo;
    EXPECT_EQ(RawlogReader::describeExternalImages(stereo, "described.rawlog"), "");
    stereo.imageLeft.setExternalStorage("present.png");
    stereo.imageRight.setExternalStorage("missing.png");
    const std::string left = "'" + (images / "present.png").string() + "'";
    const std::string right = "'" + (images / "missing.png").string() + "'";
    EXPECT_EQ(RawlogReader::describeExternalImages(stereo, "described.rawlog"),
              "images " + left + ", " + right + " (no such file: " + right +
                  "; the external images of described.rawlog are read from the folder "
                  "described_Images beside it, else from Images)");
}
