#pragma once

#include <mrpt/img/CImage.h>

namespace mrpt_vslam::core {

/** Checks that `image` has the size of the camera model it is read with: a model calibrated for
 *  another size puts every pixel at a wrong bearing. Throws std::invalid_argument "the image is
 *  WxH px but the camera model is WxH px (width x height)". Loads an externally stored image. */
void requireImageSize(const mrpt::img::CImage& image, int width, int height);

}  // namespace mrpt_vslam::core
