#include <gtest/gtest.h>
#include <mrpt_vslam/core/ImageSize.h>

#include <stdexcept>
#include <string>

using mrpt_vslam::core::requireImageSize;

TEST(ImageSize, TheCameraModelsSizeOnlyPasses)
{
    const mrpt::img::CImage image(640, 480, mrpt::img::CH_GRAY);
    EXPECT_NO_THROW(requireImageSize(image, 640, 480));
    for (const auto& [w, h] : {std::pair{1280, 960}, {640, 481}, {480, 640}}) {
        try {
            requireImageSize(image, w, h);
            ADD_FAILURE() << w << "x" << h;
        } catch (const std::invalid_argument& e) {
            EXPECT_EQ(std::string(e.what()), "the image is 640x480 px but the camera model is " +
                                                 std::to_string(w) + "x" + std::to_string(h) +
                                                 " px (width x height)");
        }
    }
}
