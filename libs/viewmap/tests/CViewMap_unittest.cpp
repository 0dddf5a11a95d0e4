#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/opengl/CEllipsoid2D.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/opengl/CSetOfTriangles.h>
#include <mrpt/opengl/CText.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/test/ScratchFolder.h>
#include <mrpt_vslam/viewmap/CViewMap.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

using mrpt::math::TPose2D;
using namespace mrpt_vslam::viewmap;

namespace {

/// n feature points whose every value depends on `seed` and the point index.
TViewFeatures makeFeatures(int n, int seed)
{
    TViewFeatures f;
    f.pixels.resize(2, n);
    f.rays.resize(3, n);
    for (int k = 0; k < n; k++) {
        const double a = 0.37 * seed + 0.11 * k;
        f.pixels(0, k) = 100.25f + 13.5f * k + seed;
        f.pixels(1, k) = 240.75f - 7.125f * k - seed;
        f.scales.push_back(1.6f + 0.4f * k);
        f.laplacian_signs.push_back(k % 2 ? int8_t{-1} : int8_t{1});
        f.rays.col(k) = Eigen::Vector3d(std::cos(a), std::sin(a), 0.3 + 0.01 * k).normalized();
        mrpt_vslam::core::USurfDescriptor::TDescriptor d;
        for (size_t i = 0; i < d.size(); i++) d[i] = 0.001f * static_cast<float>(i * 7 + k + seed);
        f.descriptors.push_back(d);
    }
    return f;
}

/// A full, positive-definite covariance of (x, y, yaw) that differs with `seed`.
Eigen::Matrix3d makeCovariance(int seed)
{
    Eigen::Matrix3d A;
    A << 0.1 + 0.01 * seed, 0.02, 0.0, -0.01, 0.2, 0.003 * seed, 0.004, 0.001, 0.05;
    return A * A.transpose();
}

TView makeView(double x, double y, double yaw, int n_features, int seed)
{
    TView v;
    v.id = 77;  // overwritten by addView()
    v.pose = TPose2D(x, y, yaw);
    v.covariance = makeCovariance(seed);
    v.timestamp = 1262304000.123456 + seed * 0.5;
    v.image_file = "Images/omni_" + std::to_string(seed) + ".png";
    v.features = makeFeatures(n_features, seed);
    return v;
}

CViewMap makeMap()
{
    CViewMap map;
    map.addView(makeView(0.5, -1.25, 0.3, 3, 1));
    map.addView(makeView(2.0, 0.75, -2.9, 2, 2));
    auto third = makeView(1234.5678, 3.5, 1.5707963267948966, 4, 3);
    third.image_file.clear();
    map.addView(third);
    return map;
}

void expectSameViews(const CViewMap& a, const CViewMap& b)
{
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); i++) {
        SCOPED_TRACE("view " + std::to_string(i));
        const TView &va = a.view(i), &vb = b.view(i);
        EXPECT_EQ(va.id, vb.id);
        EXPECT_EQ(va.pose.x, vb.pose.x);
        EXPECT_EQ(va.pose.y, vb.pose.y);
        EXPECT_EQ(va.pose.phi, vb.pose.phi);
        EXPECT_EQ(va.covariance, vb.covariance);
        EXPECT_EQ(va.timestamp, vb.timestamp);
        EXPECT_EQ(va.image_file, vb.image_file);
        ASSERT_EQ(va.features.size(), vb.features.size());
        EXPECT_EQ(va.features.pixels, vb.features.pixels);
        EXPECT_EQ(va.features.scales, vb.features.scales);
        EXPECT_EQ(va.features.laplacian_signs, vb.features.laplacian_signs);
        EXPECT_EQ(va.features.rays, vb.features.rays);
        EXPECT_EQ(va.features.descriptors, vb.features.descriptors);
    }
}

std::vector<uint8_t> serialize(const CViewMap& map)
{
    mrpt::io::CMemoryStream buf;
    auto out = mrpt::serialization::archiveFrom(buf);
    out << map;
    const auto* p = static_cast<const uint8_t*>(buf.getRawBufferData());
    return std::vector<uint8_t>(p, p + buf.getTotalBytesCount());
}

/// Reads an object from the first n bytes of `bytes`.
mrpt::serialization::CSerializable::Ptr deserialize(const std::vector<uint8_t>& bytes, size_t n)
{
    mrpt::io::CMemoryStream buf;
    buf.assignMemoryNotOwn(bytes.data(), n);
    auto in = mrpt::serialization::archiveFrom(buf);
    mrpt::serialization::CSerializable::Ptr obj;
    in >> obj;
    return obj;
}

/// The message of the exception `f` throws, "" if none.
template <typename F>
std::string errorOf(F&& f)
{
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(CViewMap, AddViewNumbersViewsAndRejectsInconsistentOnes)
{
    CViewMap map;
    EXPECT_TRUE(map.isEmpty());
    EXPECT_EQ(map.addView(makeView(1, 2, 0.1, 2, 1)), 0u);
    EXPECT_EQ(map.addView(makeView(3, 4, 0.2, 0, 2)), 1u);
    ASSERT_EQ(map.size(), 2u);
    EXPECT_EQ(map.view(0).id, 0u) << "the caller's id 77 is replaced by the index";
    EXPECT_EQ(map.view(1).id, 1u);
    EXPECT_EQ(map.views()[1].pose.x, 3.0);
    EXPECT_EQ(map.asString(), "CViewMap: 2 views, 2 feature points");

    auto ragged = makeView(0, 0, 0, 3, 4);
    ragged.features.scales.pop_back();
    EXPECT_THROW(map.addView(ragged), std::invalid_argument);
    auto nan_pose = makeView(std::nan(""), 0, 0, 1, 5);
    EXPECT_THROW(map.addView(nan_pose), std::invalid_argument);
    EXPECT_EQ(map.size(), 2u) << "rejected views are not stored";

    const std::string e = errorOf([&] { map.view(5); });
    EXPECT_NE(e.find("index 5 out of range (size 2)"), std::string::npos) << e;
    EXPECT_THROW(map.view(2), std::out_of_range);

    map.clear();
    EXPECT_TRUE(map.isEmpty());
    EXPECT_EQ(map.asString(), "CViewMap: 0 views, 0 feature points");
}

TEST(CViewMap, SetViewEstimateStoresTheEstimateAndRejectsBadInput)
{
    CViewMap map;
    map.addView(makeView(1, 2, 0.1, 1, 1));
    map.addView(makeView(3, 4, 0.2, 1, 2));
    const Eigen::Matrix3d C = makeCovariance(7);
    map.setViewEstimate(1, TPose2D(-0.5, 0.25, 3.0), C);
    EXPECT_EQ(map.view(1).pose.x, -0.5);
    EXPECT_EQ(map.view(1).pose.y, 0.25);
    EXPECT_EQ(map.view(1).pose.phi, 3.0);
    EXPECT_EQ(map.view(1).covariance, C);
    EXPECT_EQ(map.view(0).pose.x, 1.0) << "other views unchanged";

    // rounding-level asymmetry (as left by an EKF update) is accepted and removed
    Eigen::Matrix3d rounded = C;
    rounded(2, 0) += 1e-14 * C.cwiseAbs().maxCoeff();
    map.setViewEstimate(0, TPose2D(1, 2, 0.1), rounded);
    EXPECT_EQ(map.view(0).covariance, map.view(0).covariance.transpose());
    EXPECT_EQ(map.view(0).covariance(2, 0), C(0, 2));

    const std::string bad_index = errorOf([&] { map.setViewEstimate(2, TPose2D(0, 0, 0), C); });
    EXPECT_NE(bad_index.find("view 2"), std::string::npos) << bad_index;
    EXPECT_NE(bad_index.find("size 2"), std::string::npos) << bad_index;
    EXPECT_THROW(map.setViewEstimate(2, TPose2D(0, 0, 0), C), std::invalid_argument);
    EXPECT_THROW(map.setViewEstimate(0, TPose2D(0, std::numeric_limits<double>::infinity(), 0), C),
                 std::invalid_argument);
    EXPECT_THROW(map.setViewEstimate(0, TPose2D(0, 0, std::nan("")), C), std::invalid_argument);
    Eigen::Matrix3d asymmetric = C;
    asymmetric(0, 1) += 0.01;
    EXPECT_THROW(map.setViewEstimate(0, TPose2D(0, 0, 0), asymmetric), std::invalid_argument);
    Eigen::Matrix3d nan_cov = C;
    nan_cov(1, 1) = std::nan("");
    EXPECT_THROW(map.setViewEstimate(0, TPose2D(0, 0, 0), nan_cov), std::invalid_argument);
    Eigen::Matrix3d indefinite = C;
    indefinite(0, 0) = -indefinite(0, 0);
    EXPECT_EQ(errorOf([&] { map.setViewEstimate(0, TPose2D(0, 0, 0), indefinite); }),
              "CViewMap::setViewEstimate(view 0): covariance is not positive semidefinite");
    EXPECT_EQ(map.view(0).pose.x, 1.0) << "a rejected estimate changes nothing";
}

TEST(CViewMap, IsRegisteredAndDoesNotUseObservations)
{
    ASSERT_TRUE(mrpt::rtti::findRegisteredClass("mrpt_vslam::viewmap::CViewMap"));
    EXPECT_TRUE(std::dynamic_pointer_cast<CViewMap>(
        mrpt::rtti::classFactory("mrpt_vslam::viewmap::CViewMap")));

    CViewMap map = makeMap();
    mrpt::obs::CObservationOdometry obs;
    EXPECT_FALSE(map.insertObservation(obs));
    EXPECT_EQ(map.size(), 3u);
    EXPECT_FALSE(map.canComputeObservationLikelihood(obs));
    EXPECT_EQ(map.computeObservationLikelihood(obs, mrpt::poses::CPose3D()), 0.0);
    EXPECT_EQ(map.compute3DMatchingRatio(&map, mrpt::poses::CPose3D(), {}), 0.0f);
}

TEST(CViewMap, SerializationRoundTripIsExact)
{
    CViewMap map = makeMap();
    map.renderOptions.draw_ellipses = false;
    map.renderOptions.ellipse_quantiles = 2.5;
    map.renderOptions.view_size = 0.7;
    map.renderOptions.draw_ids = true;
    map.genericMapParams.enableSaveAs3DObject = false;

    const auto bytes = serialize(map);
    const auto back = std::dynamic_pointer_cast<CViewMap>(deserialize(bytes, bytes.size()));
    ASSERT_TRUE(back);
    expectSameViews(map, *back);
    EXPECT_EQ(back->view(2).image_file, "");
    EXPECT_EQ(back->view(0).image_file, "Images/omni_1.png");
    EXPECT_FALSE(back->renderOptions.draw_ellipses);
    EXPECT_EQ(back->renderOptions.ellipse_quantiles, 2.5);
    EXPECT_EQ(back->renderOptions.view_size, 0.7);
    EXPECT_TRUE(back->renderOptions.draw_ids);
    EXPECT_FALSE(back->genericMapParams.enableSaveAs3DObject);

    // every truncation throws, none crashes
    size_t thrown = 0;
    for (size_t n = 0; n < bytes.size(); n++) {
        try {
            deserialize(bytes, n);
        } catch (const std::exception&) {
            thrown++;
        }
    }
    EXPECT_EQ(thrown, bytes.size());

    // a CMultiMetricMap copy goes through the same serialization and the class registry
    mrpt::maps::CMultiMetricMap mm;
    mm.maps.push_back(std::make_shared<CViewMap>(map));
    const mrpt::maps::CMultiMetricMap copy = mm;
    const auto copied = copy.mapByClass<CViewMap>();
    ASSERT_TRUE(copied);
    EXPECT_NE(copied.get(), mm.mapByClass<CViewMap>().get());
    expectSameViews(map, *copied);
}

TEST(CViewMap, CorruptDataGivesAClearException)
{
    // One view without features or image file: the stream ends with the feature count (4
    // bytes) and MRPT's end flag (1 byte).
    CViewMap map;
    auto v = makeView(1234.5678, 2, 0.5, 0, 1);
    v.image_file.clear();
    map.addView(v);
    const auto bytes = serialize(map);
    ASSERT_TRUE(std::dynamic_pointer_cast<CViewMap>(deserialize(bytes, bytes.size())));

    auto huge = bytes;
    const uint32_t count = 2000000;
    std::memcpy(&huge[huge.size() - 5], &count, 4);
    const std::string e_huge = errorOf([&] { deserialize(huge, huge.size()); });
    EXPECT_NE(e_huge.find("view 0: 2000000 feature points"), std::string::npos) << e_huge;

    auto missing = bytes;
    const uint32_t five = 5;
    std::memcpy(&missing[missing.size() - 5], &five, 4);
    EXPECT_NE(errorOf([&] { deserialize(missing, missing.size()); }), "");

    // the pose x = 1234.5678 replaced by NaN
    auto nan_pose = bytes;
    const double x = 1234.5678, nan = std::nan("");
    size_t found = 0;
    for (size_t i = 0; i + sizeof(x) <= nan_pose.size(); i++)
        if (std::memcmp(&nan_pose[i], &x, sizeof(x)) == 0) {
            std::memcpy(&nan_pose[i], &nan, sizeof(nan));
            found++;
        }
    ASSERT_EQ(found, 1u);
    const std::string e_nan = errorOf([&] { deserialize(nan_pose, nan_pose.size()); });
    EXPECT_NE(e_nan.find("view 0: pose is not finite"), std::string::npos) << e_nan;
}

TEST(CViewMap, CreatedFromIniThroughCMultiMetricMap)
{
    mrpt::config::CConfigFileMemory ini(R"(
[Map]
viewMap_count = 1
[Map_viewMap_00_renderOpts]
view_size = 0.55
draw_ids = true
)");
    mrpt::maps::TSetOfMetricMapInitializers inits;
    inits.loadFromConfigFile(ini, "Map");
    mrpt::maps::CMultiMetricMap maps(inits);
    ASSERT_EQ(maps.maps.size(), 1u);
    const auto map = maps.mapByClass<CViewMap>();
    ASSERT_TRUE(map);
    EXPECT_EQ(map->renderOptions.view_size, 0.55);
    EXPECT_TRUE(map->renderOptions.draw_ids);
    EXPECT_TRUE(map->renderOptions.draw_ellipses) << "default kept";
    EXPECT_EQ(map->renderOptions.ellipse_quantiles, 3.0) << "default kept";
}

TEST(CViewMap, RejectsInvalidRenderOptionsNamingTheKey)
{
    // Checked on the options themselves: MRPT 2.5's TSetOfMetricMapInitializers leaks the map
    // definition when its loading throws.
    const auto errorOfLine = [](const std::string& line) {
        mrpt::config::CConfigFileMemory ini("[Map_viewMap_00_renderOpts]\n" + line);
        CViewMap::TRenderOptions o;
        return errorOf([&] { o.loadFromConfigFile(ini, "Map_viewMap_00_renderOpts"); });
    };
    EXPECT_NE(errorOfLine("view_size = 0").find("[Map_viewMap_00_renderOpts] view_size: must be"),
              std::string::npos);
    EXPECT_NE(errorOfLine("ellipse_quantiles = -1").find("ellipse_quantiles"), std::string::npos);
    EXPECT_NE(errorOfLine("ellipse_quantiles = nan").find("ellipse_quantiles"), std::string::npos);
    EXPECT_EQ(errorOfLine("view_size = 0.1\nellipse_quantiles = 2"), "");
    mrpt::config::CConfigFileMemory ini("[s]\nview_size = -0.2\n");
    CViewMap::TRenderOptions o;
    EXPECT_THROW(o.loadFromConfigFile(ini, "s"), std::invalid_argument);
}

TEST(CViewMap, WritesMapTxtAndViewsTxt)
{
    const CViewMap map = makeMap();
    mrpt_vslam::test::ScratchFolder dir("viewmap_txt");
    map.saveMetricMapRepresentationToFile(dir.file("map"));

    // map.txt: read back with the project's reader and compared to the views
    const auto file = mrpt_vslam::core::LandmarkFile::load(dir.file("map.txt"));
    EXPECT_TRUE(file.is_view_map);
    ASSERT_EQ(file.size(), 3u);
    for (size_t i = 0; i < 3; i++) {
        SCOPED_TRACE("view " + std::to_string(i));
        const auto& l = file.landmarks[i];
        const TView& v = map.view(i);
        EXPECT_EQ(l.id, static_cast<int>(i));
        EXPECT_NEAR(l.position.x, v.pose.x, 1e-8 * std::abs(v.pose.x));
        EXPECT_NEAR(l.position.y, v.pose.y, 1e-8 * std::abs(v.pose.y));
        EXPECT_NEAR(l.yaw, v.pose.phi, 1e-8 * std::abs(v.pose.phi));
        ASSERT_TRUE(l.has_cov);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                EXPECT_NEAR(l.cov(r, c), v.covariance(r, c),
                            1e-8 * std::abs(v.covariance(r, c)) + 1e-300);
    }
    std::ifstream map_txt(dir.file("map.txt"));
    std::string line;
    bool has_columns = false;
    while (std::getline(map_txt, line))
        has_columns = has_columns || line == "# id x y yaw cxx cxy cxyaw cyy cyyaw cyawyaw";
    EXPECT_TRUE(has_columns);

    // map_views.txt: parsed by hand
    std::ifstream views_txt(dir.file("map_views.txt"));
    ASSERT_TRUE(views_txt);
    std::vector<std::string> data;
    bool has_header = false;
    while (std::getline(views_txt, line)) {
        if (line.rfind("#", 0) == 0)
            has_header = has_header || line == "# id timestamp features image_file";
        else
            data.push_back(line);
    }
    EXPECT_TRUE(has_header);
    ASSERT_EQ(data.size(), 3u);
    for (size_t i = 0; i < 3; i++) {
        SCOPED_TRACE(data[i]);
        std::istringstream s(data[i]);
        unsigned id = 99;
        double timestamp = 0;
        size_t n = 0;
        std::string image;
        ASSERT_TRUE(s >> id >> timestamp >> n >> image);
        EXPECT_EQ(id, i);
        EXPECT_NEAR(timestamp, map.view(i).timestamp, 1e-6);
        EXPECT_EQ(n, map.view(i).features.size());
        EXPECT_EQ(image, i == 2 ? "-" : map.view(i).image_file);
    }
    EXPECT_NE(data[0].find("1262304000.623456"), std::string::npos) << "microseconds kept";

    const std::string missing_dir = dir.file("no_such_folder/map");
    const std::string e = errorOf([&] { map.saveMetricMapRepresentationToFile(missing_dir); });
    EXPECT_NE(e.find(missing_dir), std::string::npos) << e;
    EXPECT_THROW(map.saveMetricMapRepresentationToFile(missing_dir), std::runtime_error);
}

TEST(CViewMap, VisualizationDrawsAMarkPerViewAndSkipsDegenerateEllipses)
{
    CViewMap map;
    map.addView(makeView(1, 2, M_PI / 2, 0, 1));
    map.addView(makeView(-1, 0, 0, 0, 2));
    map.renderOptions.view_size = 0.3;

    mrpt::opengl::CSetOfObjects with;
    map.getVisualizationInto(with);
    size_t n_ellipses = 0;
    mrpt::opengl::CSetOfTriangles::Ptr marks;
    for (const auto& o : with) {
        if (auto e = std::dynamic_pointer_cast<mrpt::opengl::CEllipsoid2D>(o)) {
            if (n_ellipses++ == 0) {
                EXPECT_EQ(e->getPoseX(), 1.0);
                EXPECT_EQ(e->getPoseY(), 2.0);
                EXPECT_EQ(e->getQuantiles(), 3.0f);
                const Eigen::Matrix2d xy = map.view(0).covariance.topLeftCorner<2, 2>();
                EXPECT_EQ(Eigen::Matrix2d(e->getCovMatrix().asEigen()), xy);
            }
        }
        if (auto t = std::dynamic_pointer_cast<mrpt::opengl::CSetOfTriangles>(o)) marks = t;
    }
    EXPECT_EQ(with.size(), 3u) << "2 ellipses + 1 set of marks";
    EXPECT_EQ(n_ellipses, 2u);
    ASSERT_TRUE(marks);
    ASSERT_EQ(marks->getTrianglesCount(), 2u);
    mrpt::opengl::TTriangle t;
    marks->getTriangle(0, t);  // view 0 at (1, 2) facing +y: tip 2/3 · 0.3 ahead
    EXPECT_NEAR(t.x(0), 1.0, 1e-6);
    EXPECT_NEAR(t.y(0), 2.2, 1e-6);
    EXPECT_NEAR(t.x(1), 0.9, 1e-6);
    EXPECT_NEAR(t.y(1), 1.9, 1e-6);
    EXPECT_NEAR(t.x(2), 1.1, 1e-6);
    EXPECT_NEAR(t.y(2), 1.9, 1e-6);
    // every vertex in the marks' blue (0.1, 0.3, 1.0), not the black of a new triangle
    for (size_t i = 0; i < marks->getTrianglesCount(); i++) {
        marks->getTriangle(i, t);
        for (const auto& v : t.vertices) {
            EXPECT_EQ(v.xyzrgba.r, 25);
            EXPECT_EQ(v.xyzrgba.g, 76);
            EXPECT_EQ(v.xyzrgba.b, 255);
        }
    }

    map.renderOptions.draw_ellipses = false;
    mrpt::opengl::CSetOfObjects without;
    map.getVisualizationInto(without);
    EXPECT_EQ(without.size(), 1u);

    map.renderOptions.draw_ids = true;
    mrpt::opengl::CSetOfObjects labels;
    map.getVisualizationInto(labels);
    ASSERT_EQ(labels.size(), 3u);
    auto label = std::dynamic_pointer_cast<mrpt::opengl::CText>(*std::next(labels.begin()));
    ASSERT_TRUE(label);
    EXPECT_EQ(label->getString(), "1");

    // a view with a zero covariance (e.g. the first one, at the known start) has no ellipse
    map.renderOptions.draw_ellipses = true;
    map.renderOptions.draw_ids = false;
    map.setViewEstimate(0, TPose2D(1, 2, M_PI / 2), Eigen::Matrix3d::Zero());
    mrpt::opengl::CSetOfObjects degenerate;
    EXPECT_NO_THROW(map.getVisualizationInto(degenerate));
    EXPECT_EQ(degenerate.size(), 2u) << "view 1's ellipse + the marks";

    map.genericMapParams.enableSaveAs3DObject = false;
    mrpt::opengl::CSetOfObjects disabled;
    map.getVisualizationInto(disabled);
    EXPECT_EQ(disabled.size(), 0u);
}
