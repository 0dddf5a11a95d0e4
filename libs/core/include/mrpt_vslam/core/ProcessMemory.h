#pragma once

namespace mrpt_vslam::core {

/** Makes the C allocator keep freed memory in the process instead of returning it to the
 *  operating system (glibc: M_MMAP_THRESHOLD at its maximum, 32 MiB, and a trim threshold of
 *  1 GiB; elsewhere nothing).
 *
 *  The filters allocate and free the same few-MiB buffers every step (integral images, detector
 *  response layers, matcher workspaces). By default glibc maps each from the kernel and unmaps
 *  it on free, so every step pays the page faults of zero-filling it again; on a virtual machine
 *  that costs more than the work on the buffers (view-slam: half its time per frame).
 *  Call once at the start of a program; the apps and the benchmarks do. */
void retainFreedMemory();

}  // namespace mrpt_vslam::core
