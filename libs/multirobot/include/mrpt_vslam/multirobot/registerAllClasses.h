#pragma once

namespace mrpt_vslam::multirobot {

/** Registers every serializable class of the library with MRPT's RTTI registry. Runs by itself
 *  when the shared library is loaded; call it explicitly only from static builds. */
void registerAllClasses_multirobot();

}  // namespace mrpt_vslam::multirobot
