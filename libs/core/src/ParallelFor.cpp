#include <mrpt_vslam/core/ParallelFor.h>

#include <algorithm>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>

namespace mrpt_vslam::core {

unsigned resolveThreadCount(unsigned requested)
{
    if (requested > 0) return requested;
    return std::max(1u, std::thread::hardware_concurrency());
}

void parallelFor(size_t n, unsigned threads, const std::function<void(size_t)>& body)
{
    if (threads <= 1 || n <= 1) {
        for (size_t i = 0; i < n; i++) body(i);
        return;
    }
    std::mutex mutex;
    size_t failed_index = std::numeric_limits<size_t>::max();
    std::exception_ptr failure;
    const auto count = static_cast<long long>(n);
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(threads)
#endif
    for (long long i = 0; i < count; i++) {
        try {
            body(static_cast<size_t>(i));
        } catch (...) {
            const std::lock_guard<std::mutex> lock(mutex);
            if (static_cast<size_t>(i) < failed_index) {
                failed_index = static_cast<size_t>(i);
                failure = std::current_exception();
            }
        }
    }
    if (failure) std::rethrow_exception(failure);
}

}  // namespace mrpt_vslam::core
