#include <gtest/gtest.h>
#include <mrpt/core/exceptions.h>
#include <mrpt_vslam/core/ErrorMessage.h>

#include <stdexcept>

using mrpt_vslam::core::oneLineMessage;

TEST(ErrorMessage, KeepsOnlyTheMessageOfAnMrptException)
{
    try {
        THROW_EXCEPTION("cannot load image x.png");
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find('\n'), std::string::npos);
        EXPECT_EQ(oneLineMessage(e), "cannot load image x.png");
    }
}

TEST(ErrorMessage, JoinsTheLinesOfOtherExceptions)
{
    EXPECT_EQ(oneLineMessage(std::runtime_error("a.rawlog: bad\nentry")), "a.rawlog: bad entry");
}

namespace {
void failInsideMrpt()
{
    MRPT_START
    throw std::runtime_error("R1_RB: no usable range noise");
    MRPT_END
}
}  // namespace

TEST(ErrorMessage, KeepsOnlyTheMessageOfAStdExceptionThatMrptRethrew)
{
    try {
        failInsideMrpt();  // as CParticleFilter::executeOn() passes on a filter's error
    } catch (const std::exception& e) {
        EXPECT_EQ(oneLineMessage(e), "R1_RB: no usable range noise") << e.what();
    }
}
