#pragma once

#include <mrpt/img/CImage.h>

#include <string>
#include <string_view>

namespace mrpt_vslam::core {

/** Why the bytes of a PNG or JPEG file end early, "" when they do not (or are of another
 *  format): a PNG must reach its IEND chunk, a JPEG its end-of-image marker after the last scan.
 *  OpenCV decodes both kinds of truncated file without an error, the missing part grey. */
std::string truncationOfImageFile(std::string_view bytes);

/** Throws std::runtime_error "WHAT's file is truncated (...)" when `image` is stored in a file
 *  (MRPT's external images) that truncationOfImageFile() finds cut short. Call it before the
 *  image's pixels are first used, which loads them. Images held in memory pass. */
void requireCompleteImageFile(const mrpt::img::CImage& image, std::string_view what = "the image");

}  // namespace mrpt_vslam::core
