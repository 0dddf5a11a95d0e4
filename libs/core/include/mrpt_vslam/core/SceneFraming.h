#pragma once

#include <mrpt/math/TBoundingBox.h>
#include <mrpt/opengl/COpenGLScene.h>

#include <optional>

namespace mrpt_vslam::core {

/** @name Framing a saved scene on its content
 *  SceneViewer3D opens a `.3Dscene` with its own default camera (at the origin, 20 m away)
 *  unless the scene's followCamera flag is set: then it takes the "main" viewport's camera
 *  (or a CCamera object in the scene, which it removes), see MRPT's
 *  apps/SceneViewer3D/_DSceneViewerMain.cpp, `_DSceneViewerFrame::loadFromFile()`.
 *  @{ */
/** What a saved scene is framed on: in the "main" viewport (groups recursed into, with their
 *  poses), the vertices of lines, triangles and point clouds and the centre of spheres and text
 *  labels. Grid planes (a floor of fixed size) and uncertainty ellipsoids (their extent is only
 *  known once rendered; their landmark or view is drawn beside them) are left out.
 *  nullopt when there is none. */
std::optional<mrpt::math::TBoundingBox> sceneContentBox(const mrpt::opengl::COpenGLScene& scene);

/** Distance from the centre of `box` at which a camera looking at that centre from azimuth and
 *  elevation [deg] (MRPT's orbit camera) sees every corner of the box within `fill` (0-1] of a
 *  square field of view of `fov_deg`: max over corners of w + max(|u|, |v|) / (fill tan(fov/2)),
 *  (u, v, w) being the corner in the camera's right, up and backwards axes. */
double framingDistance(const mrpt::math::TBoundingBox& box, double azimuth_deg,
                       double elevation_deg, double fov_deg, double fill);

/** Sets the "main" viewport's camera to look down at sceneContentBox() from the south-west
 *  (azimuth 225°, elevation 50°) at framingDistance() (fill 0.9, the camera's 30° field of view,
 *  SceneViewer3D's too) and turns on the scene's followCamera flag: SceneViewer3D then opens on
 *  that camera instead of its default one at the origin. No change if the scene has no content. */
void frameSceneOnContent(mrpt::opengl::COpenGLScene& scene);
/** @} */

}  // namespace mrpt_vslam::core
