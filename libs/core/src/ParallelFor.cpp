#include <mrpt_vslam/core/ParallelFor.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

namespace mrpt_vslam::core {
namespace {

/** Worker threads that wait for the next loop a short while (kSpin) and then sleep: a filter
 *  runs a few loops per step with a little serial work between them, and waking a sleeping
 *  thread costs the caller a system call; workers spinning for longer would take the cores
 *  from other jobs when the machine is busy. One loop at a time; a loop started inside a
 *  loop's body runs serially. */
class WorkerPool {
  public:
    static WorkerPool& instance()
    {
        static WorkerPool pool;
        return pool;
    }
    ~WorkerPool()
    {
        {
            const std::lock_guard<std::mutex> lock(m_mutex);
            m_stop = true;
        }
        m_wake.notify_all();
        for (auto& t : m_workers) t.join();
    }

    void run(size_t n, unsigned threads, const std::function<void(size_t, size_t)>& body,
             const std::function<void()>& first)
    {
        const std::lock_guard<std::mutex> one_loop(m_loop_mutex);
        while (m_workers.size() + 1 < threads)
            m_workers.emplace_back([this, id = m_workers.size()] { serve(id); });
        if (m_shares.size() < threads) m_shares = std::vector<Share>(threads);
        {
            const std::lock_guard<std::mutex> lock(m_mutex);
            m_body = &body;
            // thread t's share first (parallelFor()), in chunks (takeChunk()): a thread the
            // system holds back delays the loop by one chunk, not by its share
            m_min_chunk = std::max<size_t>(1, n / (64 * threads));
            for (unsigned t = 0; t < threads; t++) {
                m_shares[t].next = n * t / threads;
                m_shares[t].end = n * (t + 1) / threads;
            }
            m_failed_index = std::numeric_limits<size_t>::max();
            m_failure = nullptr;
            m_participants = threads - 1;
            m_active = threads - 1;
            m_generation++;
        }
        m_wake.notify_all();
        std::exception_ptr first_failure;
        if (first) {
            t_inside = true;  // a loop inside `first` runs serially
            try {
                first();
            } catch (...) {
                first_failure = std::current_exception();
            }
            t_inside = false;
        }
        work(0);
        spinWhile([this] { return m_active.load(std::memory_order_relaxed) != 0; });
        std::unique_lock<std::mutex> lock(m_mutex);
        m_done.wait(lock, [this] { return m_active == 0; });
        if (first_failure) std::rethrow_exception(first_failure);
        if (m_failure) std::rethrow_exception(m_failure);
    }

  private:
    static constexpr std::chrono::microseconds kSpin{100};
    /// The indices [next, end) of a thread's share not yet taken (a cache line each).
    struct alignas(64) Share {
        std::atomic<size_t> next{0};
        size_t end = 0;
    };

    /// Calls `busy` until it is false or kSpin has passed.
    template <class Busy>
    static void spinWhile(Busy&& busy)
    {
        const auto until = std::chrono::steady_clock::now() + kSpin;
        for (unsigned i = 1; busy(); i++)
            if (i % 64 == 0 && std::chrono::steady_clock::now() > until) return;
    }

    void serve(size_t id)
    {
        uint64_t seen = 0;
        std::unique_lock<std::mutex> lock(m_mutex);
        for (;;) {
            lock.unlock();
            spinWhile([&] { return m_generation.load(std::memory_order_relaxed) == seen; });
            lock.lock();
            m_wake.wait(lock, [&] { return m_stop || m_generation != seen; });
            if (m_stop) return;
            seen = m_generation;
            if (id >= m_participants) continue;
            lock.unlock();
            work(id + 1);
            lock.lock();
            if (--m_active == 0) m_done.notify_all();
        }
    }

    /// Runs the chunks of share `own`, then those left in the others.
    void work(size_t own)
    {
        t_inside = true;
        const size_t shares = m_participants + 1;
        for (size_t s = 0; s < shares; s++) {
            Share& share = m_shares[(own + s) % shares];
            size_t begin = 0, end = 0;
            while (takeChunk(share, shares, begin, end)) runChunk(begin, end);
        }
        t_inside = false;
    }

    /** Takes the next chunk [begin, end) of a share: 1 / (2 shares) of what is left of it, at
     *  least m_min_chunk. Large first (fewer chunk starts, where the body has not requested
     *  anything ahead), small at the end, where the others may wait for the thread that took
     *  the last chunk. */
    bool takeChunk(Share& share, size_t shares, size_t& begin, size_t& end)
    {
        begin = share.next.load(std::memory_order_relaxed);
        do {
            if (begin >= share.end) return false;
            end = std::min(share.end,
                           begin + std::max(m_min_chunk, (share.end - begin) / (2 * shares)));
        } while (!share.next.compare_exchange_weak(begin, end));
        return true;
    }

    void runChunk(size_t begin, size_t end)
    {
        for (size_t i = begin; i < end; i++) {
            try {
                (*m_body)(i, end);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(m_mutex);
                if (i < m_failed_index) {
                    m_failed_index = i;
                    m_failure = std::current_exception();
                }
            }
        }
    }

  public:
    static thread_local bool t_inside;  ///< this thread is running a loop's body

  private:
    std::mutex m_loop_mutex;  ///< one loop at a time
    std::mutex m_mutex;
    std::condition_variable m_wake, m_done;
    std::vector<std::thread> m_workers;
    bool m_stop = false;
    std::atomic<uint64_t> m_generation{0};
    const std::function<void(size_t, size_t)>* m_body = nullptr;
    size_t m_min_chunk = 1, m_participants = 0;
    std::atomic<size_t> m_active{0};
    std::vector<Share> m_shares;
    size_t m_failed_index = 0;
    std::exception_ptr m_failure;
};
thread_local bool WorkerPool::t_inside = false;

}  // namespace

unsigned resolveThreadCount(unsigned requested)
{
    if (requested > 0) return requested;
    return std::max(1u, std::thread::hardware_concurrency());
}

void parallelForAhead(size_t n, unsigned threads, const std::function<void(size_t, size_t)>& body,
                      const std::function<void()>& first)
{
    if (threads <= 1 || n <= 1 || WorkerPool::t_inside) {
        if (first) first();
        for (size_t i = 0; i < n; i++) body(i, n);
        return;
    }
    WorkerPool::instance().run(n, static_cast<unsigned>(std::min<size_t>(threads, n)), body, first);
}

void parallelFor(size_t n, unsigned threads, const std::function<void(size_t)>& body,
                 const std::function<void()>& first)
{
    parallelForAhead(
        n, threads, [&body](size_t i, size_t) { body(i); }, first);
}

}  // namespace mrpt_vslam::core
