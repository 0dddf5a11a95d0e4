#include <gtest/gtest.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <filesystem>
#include <fstream>
#include <string>

using mrpt_vslam::core::LandmarkFile;
namespace fs = std::filesystem;

namespace {

const mrpt_vslam::test::ScratchFolder& scratch()
{
    static const mrpt_vslam::test::ScratchFolder folder("LandmarkFile_unittest");
    return folder;
}

std::string writeTemp(const std::string& name, const std::string& text)
{
    return scratch().write(name, text);
}

std::string loadError(const std::string& file)
{
    try {
        LandmarkFile::load(file);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return {};
}

}  // namespace

TEST(LandmarkFile, ReadsXyzWithLineOrderIds)
{
    const auto f = LandmarkFile::load(writeTemp("xyz.txt", "# x y z\n1 2 3\n\n-4.5 5 0.25\n"));
    ASSERT_EQ(f.size(), 2u);
    EXPECT_FALSE(f.is_view_map);
    EXPECT_EQ(f.landmarks[0].id, 0);
    EXPECT_EQ(f.landmarks[1].id, 1);
    EXPECT_DOUBLE_EQ(f.landmarks[1].position.x, -4.5);
    EXPECT_DOUBLE_EQ(f.landmarks[1].position.z, 0.25);
    EXPECT_FALSE(f.landmarks[0].has_cov);
}

TEST(LandmarkFile, ReadsIdXyz)
{
    const auto f = LandmarkFile::load(writeTemp("idxyz.txt", "# id x y z\n17 1 2 3\n4 5 6 7\n"));
    ASSERT_EQ(f.size(), 2u);
    EXPECT_EQ(f.landmarks[0].id, 17);
    EXPECT_EQ(f.landmarks[1].id, 4);
    EXPECT_DOUBLE_EQ(f.landmarks[1].position.y, 6.0);
}

TEST(LandmarkFile, ReadsMapWithCovariance)
{
    const auto f = LandmarkFile::load(writeTemp(
        "map.txt", "# id x y z cxx cxy cxz cyy cyz czz\n3 1 2 3 0.1 0.01 0.02 0.2 0.03 0.3\n"));
    ASSERT_EQ(f.size(), 1u);
    const auto& lm = f.landmarks[0];
    EXPECT_TRUE(lm.has_cov);
    EXPECT_DOUBLE_EQ(lm.cov(0, 0), 0.1);
    EXPECT_DOUBLE_EQ(lm.cov(1, 0), 0.01);
    EXPECT_DOUBLE_EQ(lm.cov(0, 2), 0.02);
    EXPECT_DOUBLE_EQ(lm.cov(2, 1), 0.03);
    EXPECT_DOUBLE_EQ(lm.cov(2, 2), 0.3);
}

TEST(LandmarkFile, RecognisesViewMapFromHeader)
{
    const auto f = LandmarkFile::load(writeTemp(
        "views.txt", "# id x y yaw cxx cxy cxyaw cyy cyyaw cyawyaw\n0 1 2 0.5 1 0 0 1 0 1\n"));
    ASSERT_EQ(f.size(), 1u);
    EXPECT_TRUE(f.is_view_map);
    EXPECT_DOUBLE_EQ(f.landmarks[0].yaw, 0.5);
    EXPECT_DOUBLE_EQ(f.landmarks[0].position.z, 0.0);
}

TEST(LandmarkFile, SaveLoadRoundTrip)
{
    LandmarkFile f;
    for (int i = 0; i < 3; i++) {
        mrpt_vslam::core::TLandmark lm;
        lm.id = 10 + i;
        lm.position = {0.1 * i, -1.0 * i, 2.5};
        lm.cov = Eigen::Matrix3d::Identity() * (i + 1);
        lm.cov(0, 1) = lm.cov(1, 0) = 0.125;
        lm.has_cov = true;
        f.landmarks.push_back(lm);
    }
    const auto path = (scratch().path() / "rt.txt").string();
    f.save(path, "round trip");
    const auto back = LandmarkFile::load(path);
    ASSERT_EQ(back.size(), 3u);
    for (int i = 0; i < 3; i++) {
        EXPECT_EQ(back.landmarks[i].id, 10 + i);
        EXPECT_NEAR((back.landmarks[i].position - f.landmarks[i].position).norm(), 0, 1e-9);
        EXPECT_TRUE(back.landmarks[i].cov.isApprox(f.landmarks[i].cov, 1e-9));
    }
}

TEST(LandmarkFile, BadColumnCountNamesFileAndLine)
{
    const auto path = writeTemp("cols.txt", "1 2 3\n1 2\n");
    const auto msg = loadError(path);
    EXPECT_NE(msg.find(path + ":2:"), std::string::npos) << msg;
}

TEST(LandmarkFile, ChangingColumnCountIsAnError)
{
    const auto path = writeTemp("mixed.txt", "1 2 3\n# c\n0 1 2 3\n");
    EXPECT_NE(loadError(path).find(path + ":3:"), std::string::npos);
}

TEST(LandmarkFile, NonNumberNamesFileAndLine)
{
    const auto path = writeTemp("word.txt", "0 1 2 3\n1 1 two 3\n");
    const auto msg = loadError(path);
    EXPECT_NE(msg.find(path + ":2:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("two"), std::string::npos) << msg;
}

TEST(LandmarkFile, RepeatedOrFractionalIdIsAnError)
{
    const auto rep = writeTemp("rep.txt", "0 1 2 3\n0 4 5 6\n");
    EXPECT_NE(loadError(rep).find(rep + ":2:"), std::string::npos);
    const auto frac = writeTemp("frac.txt", "0.5 1 2 3\n");
    EXPECT_NE(loadError(frac).find(frac + ":1:"), std::string::npos);
}

TEST(LandmarkFile, NegativeVarianceIsAnError)
{
    const auto path = writeTemp("negvar.txt", "0 1 2 3 -1 0 0 1 0 1\n");
    EXPECT_NE(loadError(path).find(path + ":1:"), std::string::npos);
}

TEST(LandmarkFile, MissingFileNamesTheFile)
{
    const auto path = (scratch().path() / "missing.txt").string();
    fs::remove(path);
    EXPECT_EQ(loadError(path).rfind(path + ":", 0), 0u);
}

// A map may be empty; the true landmarks may not (a run scores its map against them).
TEST(LandmarkFile, TrueLandmarksWithoutALandmarkAreAnError)
{
    const auto path = writeTemp("empty.txt", "# id x y z\n");
    EXPECT_TRUE(LandmarkFile::load(path).empty());
    try {
        LandmarkFile::loadTrueLandmarks(path);
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), path + ": no landmarks");
    }
    EXPECT_EQ(LandmarkFile::loadTrueLandmarks(writeTemp("one.txt", "7 1 2 3\n")).size(), 1u);
}
