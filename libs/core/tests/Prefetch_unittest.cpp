#include <gtest/gtest.h>
#include <mrpt_vslam/core/Prefetch.h>

#include <cstdint>
#include <set>

using mrpt_vslam::core::cacheLineOffsets;
using mrpt_vslam::core::kCacheLine;

namespace {
/// Whether the offsets, inside an object of n bytes, reach every line of it at every alignment.
template <size_t N>
void expectEveryLineReached()
{
    constexpr auto offsets = cacheLineOffsets<N>();
    for (const size_t o : offsets) EXPECT_LT(o, N);
    for (std::uintptr_t start = 0; start < 2 * kCacheLine; start++) {
        std::set<std::uintptr_t> lines, reached;
        for (size_t i = 0; i < N; i++) lines.insert((start + i) / kCacheLine);
        for (const size_t o : offsets) reached.insert((start + o) / kCacheLine);
        ASSERT_EQ(lines, reached) << N << " bytes at offset " << start;
    }
}
}  // namespace

// Against the line of every byte, for sizes below, at and above one, two and three lines.
TEST(Prefetch, OffsetsReachEveryLineOfTheObject)
{
    expectEveryLineReached<1>();
    expectEveryLineReached<8>();
    expectEveryLineReached<63>();
    expectEveryLineReached<64>();
    expectEveryLineReached<65>();
    expectEveryLineReached<104>();
    expectEveryLineReached<128>();
    expectEveryLineReached<129>();
    expectEveryLineReached<191>();
    expectEveryLineReached<192>();
    expectEveryLineReached<1667>();
}
