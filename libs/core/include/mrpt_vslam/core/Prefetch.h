#pragma once

#include <cstddef>
#include <cstdint>

namespace mrpt_vslam::core {

/// Cache line size of the machines the requests ahead are made for [bytes].
inline constexpr std::uintptr_t kCacheLine = 64;

/// Calls f(line) for each cache line holding a byte of [p, p + n), in increasing address order.
template <class F>
void forEachCacheLine(const void* p, size_t n, F&& f)
{
    if (n == 0) return;
    const auto begin = reinterpret_cast<std::uintptr_t>(p);
    for (std::uintptr_t line = begin & ~(kCacheLine - 1); line < begin + n; line += kCacheLine)
        f(reinterpret_cast<const void*>(line));
}

enum class TPrefetchFor : int { Read = 0, Write = 1 };

/** Starts loading every cache line of the n bytes at p, to be read or written soon: a loop
 *  bound by memory requests what it reads a few iterations ahead, so that the misses overlap.
 *  A hint only: it changes nothing. */
template <TPrefetchFor For = TPrefetchFor::Read>
void prefetchBytes(const void* p, size_t n)
{
    forEachCacheLine(p, n,
                     [](const void* line) { __builtin_prefetch(line, static_cast<int>(For)); });
}

/// prefetchBytes() of the whole of *p; nothing for a null p.
template <TPrefetchFor For = TPrefetchFor::Read, class T>
void prefetchObject(const T* p)
{
    if (p) prefetchBytes<For>(p, sizeof(T));
}

}  // namespace mrpt_vslam::core
