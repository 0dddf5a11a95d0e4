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
    ImageNoise = 3,  ///< sensor noise of the rendered images
    Textures = 4     ///< procedural textures of a world (seeded from its texture seed, not --seed)
};

/** Seed of one stream: the SplitMix64 finaliser applied to (seed, stream, index), folded to 32
 *  bits. `index` splits a stream into independent sub-streams: 0 is the stream of a single-robot
 *  scenario; the robots of a team use 1, 2, ... (R1, R2, ...), so each robot draws its own
 *  numbers and adding a robot to a team changes nothing for the others; the faces of a world
 *  use their index + 1 for their textures. */
uint32_t deriveStreamSeed(uint64_t seed, RandomStream stream, uint32_t index = 0);

}  // namespace mrpt_vslam::sim
