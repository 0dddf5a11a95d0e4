#pragma once

#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt/vision/CStereoRectifyMap.h>

namespace mrpt_vslam::multirobot {

/** Rectifies the stereo pairs of a head whose calibration is not rectified (lens distortion, a
 *  right camera turned or off the left one's x axis) with MRPT's CStereoRectifyMap (OpenCV's
 *  stereoRectify() and remap, alpha 0: only valid pixels), for StereoFrontEnd.
 *
 *  The rectified pair: the rectified images and calibration (no distortion, the same f_x, f_y
 *  and c_y, the principal points' columns possibly apart: StereoGeometry::disparityOffset()),
 *  the right camera at (B, 0, 0) of the left one, B the distance between the optical centres,
 *  and the camera pose of the rectified left camera: the stated pose turned by R1ᵀ, where R1
 *  takes a point from the left camera's frame into the rectified one's.
 *  CStereoRectifyMap::rectify(CObservationStereoImages&), as `rawlog-edit --stereo-rectify`
 *  calls it in MRPT 2.5, turns the pose by R1 instead, off by twice the left camera's turn.
 *
 *  The maps are made again only when the calibration changes. */
class StereoRectifier {
  public:
    /** The rectified pair of `obs`, whose calibration must be finite, of the plumb-bob model,
     *  and of one image size for both cameras, equal to that of its images.
     *  \throw std::invalid_argument (one line) otherwise. */
    mrpt::obs::CObservationStereoImages rectify(const mrpt::obs::CObservationStereoImages& obs);

  private:
    mrpt::vision::CStereoRectifyMap m_map;
};

}  // namespace mrpt_vslam::multirobot
