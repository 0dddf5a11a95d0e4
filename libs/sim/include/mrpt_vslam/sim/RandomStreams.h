#pragma once

#include <cstdint>

namespace mrpt_vslam::sim {

/** Independent random-number streams of a simulation. Each stream gets its own
 *  mrpt::random::CRandomGenerator seeded with deriveStreamSeed(seed, stream), so that changing
 *  how many numbers one stream draws (e.g. the image noise) never changes another one (e.g. the
 *  odometry noise or the bearings). */
enum class RandomStream : uint32_t {
    Odometry = 1,    ///< odometry increment noise and heading drift
    Detections = 2,  ///< bearing noise and spurious reflections
    ImageNoise = 3   ///< sensor noise of the rendered images
};

/** Seed of one stream: the SplitMix64 finaliser applied to (seed, stream), folded to 32 bits. */
uint32_t deriveStreamSeed(uint64_t seed, RandomStream stream);

}  // namespace mrpt_vslam::sim
