#pragma once

namespace mrpt_vslam::viewmap {

/** Registers every serializable class of the library with MRPT's RTTI registry. Runs by itself
 *  when the shared library is loaded; call it explicitly only from static builds. */
void registerAllClasses_viewmap();

}  // namespace mrpt_vslam::viewmap
