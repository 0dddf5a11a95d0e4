#pragma once

#include <mrpt/bayes/CParticleFilterData.h>

#include <vector>

namespace mrpt_vslam::core {

/** mrpt::bayes::CParticleFilterDataImpl whose resampling leaves equal weights.
 *
 *  MRPT 2.5's CParticleFilterCapable::performResampling(options) resets the log-weights of only
 *  `out_particle_count` particles, 0 by default, which is how CParticleFilter::executeOn calls
 *  it: the resampled copies keep their parents' weights, so every later step weighs the set by
 *  its old weights a second time. Resampling always goes through performSubstitution(), so this
 *  class sets every log-weight to 0 there. Use it in place of CParticleFilterDataImpl. */
template <class Derived, class ParticleList>
class ParticleFilterDataImpl : public mrpt::bayes::CParticleFilterDataImpl<Derived, ParticleList> {
  public:
    void performSubstitution(const std::vector<size_t>& indx) override
    {
        mrpt::bayes::CParticleFilterDataImpl<Derived, ParticleList>::performSubstitution(indx);
        for (auto& p : static_cast<Derived*>(this)->m_particles) p.log_w = 0;
    }
};

}  // namespace mrpt_vslam::core
