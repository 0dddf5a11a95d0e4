#pragma once

#include <mrpt/img/CImage.h>

#include <string>
#include <string_view>

namespace mrpt_vslam::core {

/** What is wrong with the bytes of a PNG or JPEG file, "" when nothing is found (or they are of
 *  another format): "truncated (...)" when a PNG ends before its IEND chunk or a JPEG before its
 *  end-of-image marker after the last scan; "corrupt (...)" when a PNG chunk fails its CRC.
 *  OpenCV decodes a truncated JPEG without an error, its missing part grey; a damaged JPEG's
 *  scans are not checked (they have no checksum). */
std::string imageFileDamage(std::string_view bytes);

/** Throws std::runtime_error "WHAT's file is DAMAGE" when `image` is stored in a file (MRPT's
 *  external images) in which imageFileDamage() finds DAMAGE. Call it before the image's pixels
 *  are first used, which loads them. Images held in memory pass. */
void requireIntactImageFile(const mrpt::img::CImage& image, std::string_view what = "the image");

}  // namespace mrpt_vslam::core
