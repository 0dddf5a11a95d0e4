#pragma once

#include <cstddef>
#include <functional>

namespace mrpt_vslam::core {

/** The number of threads `--threads N` asks for: N if N > 0, else every core of the machine. */
unsigned resolveThreadCount(unsigned requested);

/** Runs body(i) for every i in [0, n) on up to `threads` threads (OpenMP, static schedule).
 *
 *  The bodies must not write state that another index reads or writes; then the result does
 *  not depend on the thread count. With threads <= 1, or without OpenMP, it is a plain loop.
 *  If bodies throw, the exception of the lowest index is rethrown once all have finished, so
 *  which error is reported does not depend on the thread count either. */
void parallelFor(size_t n, unsigned threads, const std::function<void(size_t)>& body);

}  // namespace mrpt_vslam::core
