#pragma once

#include <cstddef>
#include <functional>

namespace mrpt_vslam::core {

/** The number of threads `--threads N` asks for: N if N > 0, else every core of the machine. */
unsigned resolveThreadCount(unsigned requested);

/** Runs body(i) for every i in [0, n) on up to `threads` threads: the caller's and workers
 *  that sleep between loops. Thread t starts on the t-th of `threads` equal shares of [0, n)
 *  (so a loop over particles runs each where the loop before left it, in that core's cache),
 *  taking it in chunks that shrink as the share empties (a 1 / (2 threads) part of what is
 *  left, at least n / (64 threads)), and then takes the chunks left in the other shares: the
 *  threads finish within about one small chunk of each other.
 *
 *  The bodies must not write state that another index reads or writes; then the result does
 *  not depend on the thread count. With threads <= 1, n <= 1, or inside another loop's body,
 *  it is a plain loop. If bodies throw, the exception of the lowest index is rethrown once the
 *  loop has finished, so which error is reported does not depend on the thread count either.
 *
 *  `first`, if given, is run by the calling thread before it takes its share (the others
 *  start on theirs at once and take what it leaves): serial work that the loop's bodies do
 *  not touch, overlapped with the loop. Loops inside it run serially. If it throws, its
 *  exception is the one rethrown (serially, before any body has run). */
void parallelFor(size_t n, unsigned threads, const std::function<void(size_t)>& body,
                 const std::function<void()>& first = {});

/** parallelFor() for a body that reads ahead: body(i, end), where the indices (i, end) are the
 *  ones this thread runs next, in increasing order, and no other thread runs. The body may read
 *  their state, which no other body writes while it runs (to request their memory before it
 *  is needed, say); `end` is n when the loop runs serially. */
void parallelForAhead(size_t n, unsigned threads, const std::function<void(size_t, size_t)>& body,
                      const std::function<void()>& first = {});

}  // namespace mrpt_vslam::core
