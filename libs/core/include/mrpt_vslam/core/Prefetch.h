#pragma once

#include <array>
#include <cstddef>
#include <utility>

namespace mrpt_vslam::core {

/// Cache line size of the machines the requests ahead are made for [bytes].
inline constexpr size_t kCacheLine = 64;

/** The offsets prefetchObject() requests in an object of N bytes: one every kCacheLine bytes
 *  from its start, and its last byte, so that each cache line holding a byte of it gets one
 *  whatever the object's alignment. */
template <size_t N>
constexpr std::array<size_t, (N + kCacheLine - 1) / kCacheLine + 1> cacheLineOffsets()
{
    static_assert(N > 0);
    std::array<size_t, (N + kCacheLine - 1) / kCacheLine + 1> offsets{};
    for (size_t j = 0; j + 1 < offsets.size(); j++) offsets[j] = j * kCacheLine;
    offsets.back() = N - 1;
    return offsets;
}

namespace detail {
/** A request for the cache line of p that the compiler keeps: GCC deletes a call to a function
 *  that only prefetches, and a loop whose body only does, as code with no effect. */
[[gnu::always_inline]] inline void prefetchLine(const char* p)
{
#if defined(__x86_64__) || defined(__i386__)
    asm volatile("prefetcht0 %0" : : "m"(*p));
#else
    __builtin_prefetch(p);
    asm volatile("" : : "r"(p));
#endif
}

template <size_t N, size_t... J>
[[gnu::always_inline]] inline void prefetchOffsets(const char* bytes, std::index_sequence<J...>)
{
    constexpr auto offsets = cacheLineOffsets<N>();
    (prefetchLine(bytes + offsets[J]), ...);
}
}  // namespace detail

/** Starts loading every cache line of *p (nothing for a null p): a loop bound by memory
 *  requests what it reads a few iterations ahead, so that the misses overlap. A hint only: it
 *  changes nothing. */
template <class T>
[[gnu::always_inline]] inline void prefetchObject(const T* p)
{
    if (!p) return;
    detail::prefetchOffsets<sizeof(T)>(
        reinterpret_cast<const char*>(p),
        std::make_index_sequence<cacheLineOffsets<sizeof(T)>().size()>());
}

}  // namespace mrpt_vslam::core
