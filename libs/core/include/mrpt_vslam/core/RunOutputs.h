#pragma once

#include <mrpt/img/TColor.h>
#include <mrpt/maps/CMetricMap.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/serialization/CSerializable.h>
#include <mrpt_vslam/core/TumTrajectory.h>

#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** @name Writing the MRPT files of a run folder (doc/data-formats.md)
 *  Every function writes to `FILE.tmp` and renames it when complete, so a failed run never
 *  leaves a partial file under the final name.
 *  @{ */

/// Serializes one object gz-compressed (`final_map.gz`), readable with `archive >> obj`.
void saveObjectGz(const mrpt::serialization::CSerializable& obj, const std::string& file);

/** A map's `saveMetricMapRepresentationToFile()` files in `out_dir` under `prefix`
 *  (`<prefix>.txt`, plus whatever else the map writes, e.g. `<prefix>_descriptors.txt`), each
 *  renamed into place when complete. */
void saveMapFiles(const mrpt::maps::CMetricMap& map, const std::string& out_dir,
                  const std::string& prefix);
/** The final map of a run into `out_dir`: saveMapFiles() under the prefix `map` and
 *  `final_map.gz`. */
void saveFinalMap(const mrpt::maps::CMetricMap& map, const std::string& out_dir);

/// Saves a scene as MRPT's `.3Dscene` (opens in SceneViewer3D without any plugin).
void saveScene(const mrpt::opengl::COpenGLScene& scene, const std::string& file);

/// A trajectory as a polyline in the scene, with a text label at its end.
mrpt::opengl::CSetOfObjects::Ptr trajectoryAsLines(const TumTrajectory& path,
                                                   const mrpt::img::TColorf& color,
                                                   const std::string& label, float width = 2);

/// Points (e.g. true landmarks) as small crosses of a given size [m].
mrpt::opengl::CSetOfLines::Ptr pointsAsCrosses(const std::vector<mrpt::math::TPoint3D>& points,
                                               const mrpt::img::TColorf& color, double size = 0.3);
/** @} */

}  // namespace mrpt_vslam::core
