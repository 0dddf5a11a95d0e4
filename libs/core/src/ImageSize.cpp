#include <mrpt/core/format.h>
#include <mrpt_vslam/core/ImageSize.h>

#include <stdexcept>

namespace mrpt_vslam::core {

void requireImageSize(const mrpt::img::CImage& image, int width, int height)
{
    if (image.getWidth() != static_cast<size_t>(width) ||
        image.getHeight() != static_cast<size_t>(height))
        throw std::invalid_argument(mrpt::format(
            "the image is %zux%zu px but the camera model is %dx%d px (width x height)",
            image.getWidth(), image.getHeight(), width, height));
}

}  // namespace mrpt_vslam::core
