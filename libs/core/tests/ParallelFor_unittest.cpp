#include <gtest/gtest.h>
#include <mrpt_vslam/core/ParallelFor.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using mrpt_vslam::core::parallelFor;
using mrpt_vslam::core::resolveThreadCount;

TEST(ParallelFor, EveryIndexRunsOnceWhateverTheThreadCount)
{
    for (const unsigned threads : {0u, 1u, 2u, 3u, 7u})
        for (const size_t n : {size_t{0}, size_t{1}, size_t{5}, size_t{1000}}) {
            std::vector<std::atomic<int>> calls(n);
            parallelFor(n, threads, [&](size_t i) { calls[i]++; });
            for (size_t i = 0; i < n; i++)
                ASSERT_EQ(calls[i].load(), 1) << "index " << i << ", " << threads << " threads";
        }
}

TEST(ParallelFor, AThreadDoneWithItsShareTakesTheOthers)
{
    // The thread that runs index 0 waits until 60 of the other 99 indices are done: the other
    // thread has to run more than its own half of them. Without taking chunks from the first
    // thread's share it would finish at 50 and the wait would time out.
    constexpr size_t n = 100;
    std::atomic<size_t> done{0};
    std::atomic<bool> timed_out{false};
    std::vector<std::atomic<int>> calls(n);
    parallelFor(n, 2, [&](size_t i) {
        if (i == 0) {
            const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
            while (done.load() < 60 && !timed_out)
                if (std::chrono::steady_clock::now() > until) timed_out = true;
        }
        calls[i]++;
        done++;
    });
    EXPECT_FALSE(timed_out) << "the loop did not balance between its threads";
    for (size_t i = 0; i < n; i++) ASSERT_EQ(calls[i].load(), 1) << "index " << i;
}

TEST(ParallelFor, ChunksShrinkAsEachShareEmpties)
{
    // The chunks are read from parallelForAhead()'s `end`, the end of the chunk being run: a
    // quarter of a share first (two threads), never growing, the last no more than n / 128.
    constexpr size_t n = 6400, share = n / 2, min_chunk = n / 128;
    std::vector<std::atomic<size_t>> chunk_end(n);
    mrpt_vslam::core::parallelForAhead(n, 2, [&](size_t i, size_t end) { chunk_end[i] = end; });
    for (const size_t first : {size_t{0}, share}) {
        std::vector<size_t> sizes;
        for (size_t begin = first; begin < first + share; begin = chunk_end[begin]) {
            ASSERT_GT(chunk_end[begin].load(), begin);
            ASSERT_LE(chunk_end[begin].load(), first + share) << "a chunk across two shares";
            sizes.push_back(chunk_end[begin] - begin);
        }
        EXPECT_EQ(sizes.front(), share / 4) << "share at " << first;
        for (size_t c = 1; c < sizes.size(); c++)
            EXPECT_LE(sizes[c], sizes[c - 1]) << "chunk " << c << " of the share at " << first;
        EXPECT_LE(sizes.back(), min_chunk) << "share at " << first;
    }
}

TEST(ParallelFor, ThrowsTheErrorOfTheLowestFailingIndex)
{
    for (const unsigned threads : {1u, 2u, 4u}) {
        try {
            parallelFor(100, threads, [&](size_t i) {
                if (i == 37 || i == 80 || i == 95) throw std::runtime_error(std::to_string(i));
            });
            ADD_FAILURE() << "no exception, " << threads << " threads";
        } catch (const std::runtime_error& e) {
            EXPECT_STREQ(e.what(), "37") << threads << " threads";
        }
    }
}

TEST(ParallelFor, AheadGivesTheIndicesThisThreadRunsNext)
{
    // each index records its thread, its order on that thread and its `end`; every index in
    // (i, end) must then run later on the same thread
    for (const unsigned threads : {1u, 2u, 3u})
        for (const size_t n : {size_t{1}, size_t{7}, size_t{1000}}) {
            std::vector<std::thread::id> thread(n);
            std::vector<size_t> order(n), end(n);
            std::atomic<size_t> clock{0};
            mrpt_vslam::core::parallelForAhead(n, threads, [&](size_t i, size_t e) {
                thread[i] = std::this_thread::get_id();
                order[i] = clock++;
                end[i] = e;
            });
            for (size_t i = 0; i < n; i++) {
                ASSERT_GT(end[i], i) << threads << " threads, n = " << n;
                ASSERT_LE(end[i], n);
                for (size_t j = i + 1; j < end[i]; j++) {
                    ASSERT_EQ(thread[j], thread[i]) << "index " << j << " after " << i;
                    ASSERT_GT(order[j], order[i]) << "index " << j << " after " << i;
                }
            }
            if (threads == 1) {
                EXPECT_EQ(end[0], n);
            }
        }
}

TEST(ParallelFor, ThreadCountZeroMeansEveryCore)
{
    EXPECT_EQ(resolveThreadCount(3), 3u);
    EXPECT_EQ(resolveThreadCount(0), std::max(1u, std::thread::hardware_concurrency()));
}

TEST(ParallelFor, FirstRunsOnTheCallingThreadWhileTheOthersLoop)
{
    // `first` waits until another thread has run half of the bodies: with two threads the loop
    // goes on while it runs. With one thread it runs before the bodies.
    for (const unsigned threads : {1u, 2u}) {
        constexpr size_t n = 100;
        std::atomic<size_t> done{0};
        std::vector<std::atomic<int>> calls(n);
        int first_calls = 0, nested = 0;
        bool timed_out = false;
        const auto caller = std::this_thread::get_id();
        std::thread::id first_thread;
        parallelFor(
            n, threads,
            [&](size_t i) {
                calls[i]++;
                done++;
            },
            [&] {
                first_calls++;
                first_thread = std::this_thread::get_id();
                parallelFor(10, 2, [&](size_t) { nested++; });  // serial inside
                const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
                while (threads > 1 && done.load() < n / 2 && !timed_out)
                    if (std::chrono::steady_clock::now() > until) timed_out = true;
                if (threads == 1) {
                    EXPECT_EQ(done.load(), 0u);
                }
            });
        EXPECT_EQ(first_calls, 1);
        EXPECT_EQ(nested, 10);
        EXPECT_EQ(first_thread, caller);
        EXPECT_FALSE(timed_out) << "the other thread did not loop while `first` ran";
        for (size_t i = 0; i < n; i++) ASSERT_EQ(calls[i].load(), 1) << "index " << i;
    }
}

TEST(ParallelFor, FirstsErrorComesAfterTheLoopAndBeforeTheBodies)
{
    for (const unsigned threads : {1u, 2u}) {
        std::atomic<size_t> done{0};
        try {
            parallelFor(
                100, threads,
                [&](size_t i) {
                    done++;
                    if (i == 50 && threads > 1) throw std::runtime_error("body");
                },
                [] { throw std::runtime_error("first"); });
            ADD_FAILURE() << "no exception, " << threads << " threads";
        } catch (const std::runtime_error& e) {
            EXPECT_STREQ(e.what(), "first") << threads << " threads";
        }
        // with threads the others finish the loop before the error is thrown; serially
        // `first` throws before any body
        EXPECT_EQ(done.load(), threads > 1 ? 100u : 0u);
    }
}
