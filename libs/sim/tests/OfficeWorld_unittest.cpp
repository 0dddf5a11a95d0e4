#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/vector_loadsave.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/OfficeWorld.h>

#include <cmath>

#include "TestConfig.h"

using namespace mrpt_vslam::sim;

namespace {

/// The shipped office-team config, in memory so tests can change keys.
mrpt::config::CConfigFileMemory shippedConfig()
{
    std::vector<std::string> lines;
    mrpt::io::loadTextFile(lines, test::officeTeamIni());
    return mrpt::config::CConfigFileMemory(lines);
}

OfficeWorld shippedWorld()
{
    OfficeWorld w;
    w.loadFromConfigFile(shippedConfig(), "World");
    return w;
}

TexturePainter shippedPainter()
{
    TexturePainter p;
    p.loadFromConfigFile(test::officeTeamConfig(), "Textures");
    return p;
}

/// The UsageError message of loading [World] with `key` set to `value`.
std::string loadError(const std::string& key, const std::string& value)
{
    mrpt::config::CConfigFileMemory cfg = shippedConfig();
    cfg.write("World", key, value);
    OfficeWorld w;
    try {
        w.loadFromConfigFile(cfg, "World");
    } catch (const mrpt_vslam::core::UsageError& e) {
        return e.what();
    }
    return "no error";
}

/// The model built from the shipped config, once for all tests.
const TOfficeModel& shippedModel()
{
    static const TOfficeModel model = shippedWorld().build(shippedPainter());
    return model;
}

}  // namespace

TEST(OfficeWorld, ShippedLayoutIsTheSeventeenByEightMetreOffice)
{
    const OfficeWorld w = shippedWorld();
    ASSERT_EQ(w.room.size(), 4u);
    double x_min = 1e9, x_max = -1e9, y_min = 1e9, y_max = -1e9;
    for (const auto& p : w.room) {
        x_min = std::min(x_min, p.x), x_max = std::max(x_max, p.x);
        y_min = std::min(y_min, p.y), y_max = std::max(y_max, p.y);
    }
    EXPECT_DOUBLE_EQ(x_max - x_min, 17.0);
    EXPECT_DOUBLE_EQ(y_max - y_min, 8.0);
    EXPECT_EQ(w.wall_height, 2.5);
    EXPECT_EQ(w.doors.size(), 5u);
    EXPECT_EQ(w.boxes.size(), 13u);
    EXPECT_EQ(w.texture_seed, 2010u);
    // The robots' start points (Gil et al. 2010: R1 at the origin, R2 at (-4, 0)) are free.
    EXPECT_GT(w.clearance(0, 0), 1.0);
    EXPECT_GT(w.clearance(-4, 0), 1.0);
}

TEST(OfficeWorld, ClearanceAndDistanceAheadMeasureToWallsAndFurniture)
{
    const OfficeWorld w = shippedWorld();
    // (0, 0): the cabinet on the south wall (y = -1.45) is nearest, 1.45 m.
    EXPECT_NEAR(w.clearance(0, 0), 1.45, 1e-12);
    // In the cross passage between the islands (x 1.5 .. 3.5): 1 m to either.
    EXPECT_NEAR(w.clearance(2.5, 2.5), 1.0, 1e-12);
    EXPECT_LT(w.clearance(-7, 0), 0);   // outside the room
    EXPECT_LT(w.clearance(0, 2.5), 0);  // inside the west island
    EXPECT_NEAR(w.clearance(0, 2.3), -0.8, 1e-12);

    EXPECT_NEAR(w.distanceAhead(0, 0, 0, 0.5), 11.0, 1e-12);          // east wall
    EXPECT_NEAR(w.distanceAhead(2.5, 0, M_PI / 2, 0.5), 6.0, 1e-12);  // through the passage
    EXPECT_NEAR(w.distanceAhead(0, 0, M_PI / 2, 0.5), 1.5, 1e-12);    // west island
    // Above the 2 m partitions of the west island the eye sees the north wall.
    EXPECT_NEAR(w.distanceAhead(0, 0, M_PI / 2, 2.2), 6.0, 1e-12);
}

TEST(OfficeWorld, BadLayoutsFailNamingTheKey)
{
    EXPECT_NE(loadError("room", "0 0 5 0").find("[World] room"), std::string::npos);
    EXPECT_NE(loadError("room", "0 0 5 x 5 5").find("[World] room: 'x' is not a number"),
              std::string::npos);
    EXPECT_NE(loadError("doors", "2.5 -1 0.9").find("[World] doors"), std::string::npos);
    EXPECT_NE(loadError("doors", "2.5 -2").find("[World] doors"), std::string::npos);
    EXPECT_NE(loadError("desks", "0 -1.7 1 -1.2 0.75").find("overlaps"), std::string::npos)
        << "the desk overlaps the cabinet at x -1.5 .. 0.3";
    EXPECT_NE(loadError("desks", "10.5 0 11.5 1 0.75").find("inside the room"), std::string::npos);
    EXPECT_NE(loadError("shelves", "1 1 2 2").find("[World] shelves"), std::string::npos);
    EXPECT_NE(loadError("wall_height", "0.3").find("[World] wall_height"), std::string::npos);
    EXPECT_EQ(loadError("room", "-6 6 11 6 11 -2 -6 -2"), "no error") << "clockwise is fine";
}

TEST(OfficeWorld, CornersLieOnTheirFacesAndHaveConsecutiveIds)
{
    const TOfficeModel& m = shippedModel();
    // Room walls, 13 boxes × (4 sides + top), floor, ceiling.
    EXPECT_EQ(m.scene.rectangles.size(), 4u + 13 * 5 + 2);
    EXPECT_GT(m.corners.size(), 800u);
    for (size_t i = 0; i < m.corners.size(); i++) {
        const TCornerLandmark& c = m.corners[i];
        ASSERT_EQ(c.id, static_cast<int>(i) + 1);
        const TexturedRectangle& f = m.scene.rectangles[c.face];
        EXPECT_TRUE(f.isVertical());
        const Eigen::Vector3d d = c.position - f.origin();
        EXPECT_NEAR(d.dot(f.normal()), 0.0, 1e-9);
        EXPECT_GE(d.dot(f.axisS()), 0.0);
        EXPECT_LE(d.dot(f.axisS()), f.width());
        // At least corner_window (4 cm) inside the face: off the floor and the top edge.
        EXPECT_GE(c.position.z(), 0.04 - 1e-9);
        EXPECT_LE(c.position.z(), f.origin().z() - 0.04 + 1e-9);
    }
}

TEST(OfficeWorld, TexturesDependOnlyOnTheTextureSeed)
{
    const TOfficeModel& a = shippedModel();
    const TOfficeModel b = shippedWorld().build(shippedPainter());
    ASSERT_EQ(a.corners.size(), b.corners.size());
    for (size_t i = 0; i < a.corners.size(); i++)
        ASSERT_EQ(a.corners[i].position, b.corners[i].position);

    OfficeWorld other = shippedWorld();
    other.texture_seed = 7;
    const TOfficeModel c = other.build(shippedPainter());
    size_t same = 0;
    for (size_t i = 0; i < std::min(a.corners.size(), c.corners.size()); i++)
        same += a.corners[i].position == c.corners[i].position;
    EXPECT_LT(same, a.corners.size() / 10);
}
