#include <mrpt_vslam/sim/RandomStreams.h>

namespace mrpt_vslam::sim {

uint32_t deriveStreamSeed(uint64_t seed, RandomStream stream, uint32_t index)
{
    // SplitMix64 (Steele, Lea & Flood 2014) output function on a stream- and index-dependent
    // state; index 0 adds nothing, which keeps the single-robot streams as they were.
    uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (static_cast<uint64_t>(stream) + 1) +
                 0xD1B54A32D192ED03ULL * index;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return static_cast<uint32_t>(z ^ (z >> 32));
}

}  // namespace mrpt_vslam::sim
