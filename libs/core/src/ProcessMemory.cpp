#include <mrpt_vslam/core/ProcessMemory.h>

#if __has_include(<malloc.h>)
#include <malloc.h>
#endif

namespace mrpt_vslam::core {

void retainFreedMemory()
{
#if defined(__GLIBC__) && defined(M_MMAP_THRESHOLD)
    // Blocks below the threshold come from the heap (DEFAULT_MMAP_THRESHOLD_MAX on 64 bits);
    // free memory at the top of a heap goes back to the kernel only beyond the trim threshold.
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace mrpt_vslam::core
