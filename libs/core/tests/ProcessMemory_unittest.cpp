#include <gtest/gtest.h>
#include <mrpt_vslam/core/ProcessMemory.h>

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
#include <malloc.h>

#include <cstring>
#include <memory>

// An 8 MiB block, freed and allocated again, the way a filter's per-step buffers are: served
// from the heap and kept there, not mapped from the kernel and unmapped again.
TEST(ProcessMemory, FreedBlocksStayInTheProcess)
{
    constexpr size_t kBytes = 8 << 20;
    mrpt_vslam::core::retainFreedMemory();
    const size_t mapped_before = mallinfo2().hblkhd;
    for (int round = 0; round < 3; round++) {
        auto block = std::make_unique<char[]>(kBytes);
        std::memset(block.get(), round, kBytes);
        EXPECT_EQ(mallinfo2().hblkhd, mapped_before) << "round " << round;
        block.reset();
        EXPECT_GE(mallinfo2().fordblks, kBytes) << "round " << round;
    }
}
#else
TEST(ProcessMemory, FreedBlocksStayInTheProcess)
{
    GTEST_SKIP() << "glibc's allocator only (AddressSanitizer replaces it)";
}
#endif
