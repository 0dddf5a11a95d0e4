// Linked into every benchmark: the allocator set up as the apps set it, so that a benchmark
// times the filters as they run in the apps.
#include <mrpt_vslam/core/ProcessMemory.h>

namespace {
const bool kRetained = (mrpt_vslam::core::retainFreedMemory(), true);
}
