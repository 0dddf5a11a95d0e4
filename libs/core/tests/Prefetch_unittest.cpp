#include <gtest/gtest.h>
#include <mrpt_vslam/core/Prefetch.h>

#include <set>
#include <vector>

using mrpt_vslam::core::forEachCacheLine;
using mrpt_vslam::core::kCacheLine;

// The lines visited are exactly those holding a byte of the range, each once, in order:
// against the set of every byte's line, for every offset in two lines and sizes up to three.
TEST(Prefetch, VisitsEachLineOfTheRangeOnce)
{
    alignas(64) static char buffer[6 * kCacheLine];
    for (size_t offset = 0; offset < 2 * kCacheLine; offset++)
        for (size_t n = 0; n <= 3 * kCacheLine; n++) {
            const char* p = buffer + offset;
            std::set<std::uintptr_t> expected;
            for (size_t i = 0; i < n; i++)
                expected.insert(reinterpret_cast<std::uintptr_t>(p + i) / kCacheLine);
            std::vector<std::uintptr_t> visited;
            forEachCacheLine(p, n, [&](const void* line) {
                const auto a = reinterpret_cast<std::uintptr_t>(line);
                EXPECT_EQ(a % kCacheLine, 0u);
                visited.push_back(a / kCacheLine);
            });
            ASSERT_EQ(std::vector<std::uintptr_t>(expected.begin(), expected.end()), visited)
                << "offset " << offset << ", " << n << " bytes";
        }
}
