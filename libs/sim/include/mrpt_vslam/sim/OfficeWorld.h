#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/sim/TexturePainter.h>
#include <mrpt_vslam/sim/TexturedScene.h>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace mrpt_vslam::sim {

/** A box standing on the floor: a partition, cabinet, shelf or desk. */
struct TBox {
    double x_min = 0, y_min = 0, x_max = 0, y_max = 0;  ///< [m] footprint
    double height = 0;                                  ///< [m]
    TSurfaceKind front = TSurfaceKind::Wall;  ///< look of its sides (Wall for a partition)
};

/** A door in a room wall. */
struct TDoor {
    double x = 0, y = 0;  ///< [m] centre of the opening on the wall, on the floor
    double width = 0;     ///< [m]
};

/** A designed corner of the world's textures: a ground-truth landmark. */
struct TCornerLandmark {
    int id = 0;                ///< 1-based, in the order of the faces
    Eigen::Vector3d position;  ///< [m] world frame
    size_t face = 0;           ///< index of its rectangle in the scene
};

/** The built world: textured faces and their corners. */
struct TOfficeModel {
    TexturedScene scene;
    std::vector<TCornerLandmark> corners;

    /// The corners as a ground-truth landmarks file (`NAME.landmarks.txt`).
    core::LandmarkFile cornerLandmarks() const;
};

/** An office-like indoor area for the multi-robot experiment of Gil et al. 2010 (Sec. 6: "a
 *  typical office indoor environment", 17 × 8 m): vertical walls on a polygonal room outline,
 *  doors in them, and boxes standing on the floor (partitions forming islands, cabinets, shelves,
 *  desks), plus floor and ceiling. Every face is a TexturedRectangle painted by TexturePainter;
 *  the textures depend only on `texture_seed` (the world is the same for every run seed).
 *
 *  Faces in this order: room walls (outline order), then each box's sides (−y, +x, +y, −x) and
 *  top, then floor and ceiling. A face gets the texture of its kind, except that the parts of a
 *  face hidden by something standing within 0.15 m in front of it stay plain (walls: no items
 *  there below the obstacle's top; furniture: a plain panel when more than half is hidden), so
 *  that ground-truth corners are where a robot can see them. */
class OfficeWorld : public mrpt::config::CLoadableOptions {
  public:
    /// @name Parameters (ini section [World])
    /// @{
    std::vector<mrpt::math::TPoint2D> room;  ///< [m] outline (stored counter-clockwise)
    double wall_height = 2.5;                ///< [m]
    std::vector<TDoor> doors;                ///< doors in the room walls
    double door_height = 2.05;               ///< [m]
    std::vector<TBox> boxes;    ///< partitions, cabinets, shelves and desks, in that order
    uint64_t texture_seed = 1;  ///< seed of the textures
    /// @}

    /** Signed clearance [m] of the floor point (x, y): distance to the nearest wall or box
     *  footprint; negative outside the room or inside a box. */
    double clearance(double x, double y) const;

    /** Horizontal distance [m] from (x, y) along `heading` [rad] to the first wall or box
     *  taller than `eye_height` [m]. */
    double distanceAhead(double x, double y, double heading, double eye_height) const;

    /// Faces, textures and ground-truth corners (deterministic).
    TOfficeModel build(const TexturePainter& painter) const;

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                            const std::string& section) override;
};

}  // namespace mrpt_vslam::sim
