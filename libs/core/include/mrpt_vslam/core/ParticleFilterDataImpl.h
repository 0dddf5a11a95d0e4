#pragma once

#include <mrpt/bayes/CParticleFilterData.h>
#include <mrpt_vslam/core/ParallelFor.h>

#include <algorithm>
#include <vector>

namespace mrpt_vslam::core {

/** mrpt::bayes::CParticleFilterDataImpl whose resampling leaves equal weights, and which knows
 *  each particle's accumulated log-weight (the particle data's `accumulated_log_w`).
 *
 *  MRPT 2.5's CParticleFilterCapable::performResampling(options) resets the log-weights of only
 *  `out_particle_count` particles, 0 by default, which is how CParticleFilter::executeOn calls
 *  it: the resampled copies keep their parents' weights, so every later step weighs the set by
 *  its old weights a second time. Resampling always goes through performSubstitution(), so this
 *  class sets every log-weight to 0 there. Use it in place of CParticleFilterDataImpl; derived
 *  filters run their per-particle loops on m_threads. */
template <class Derived, class ParticleList>
class ParticleFilterDataImpl : public mrpt::bayes::CParticleFilterDataImpl<Derived, ParticleList> {
  public:
    /// Threads the particles are updated on (0, the default: every core). The
    /// results do not depend on it: the same seed gives the same particles bit for bit.
    void setThreadCount(unsigned threads) { m_threads = resolveThreadCount(threads); }

    void performSubstitution(const std::vector<size_t>& indx) override
    {
        mrpt::bayes::CParticleFilterDataImpl<Derived, ParticleList>::performSubstitution(indx);
        for (auto& p : static_cast<Derived*>(this)->m_particles) p.log_w = 0;
    }

    /// Multiplies a particle's weight by exp(log_w) and adds log_w to the sum Σ_t log ω_t it
    /// keeps through resampling.
    template <class Particle>
    static void addLogWeight(Particle& p, double log_w)
    {
        p.log_w += log_w;
        p.d->accumulated_log_w += log_w;
    }

    /// The particle with the largest accumulated log-weight Σ_t log ω_t (the first of equals).
    const auto& bestParticle() const
    {
        const auto& particles = static_cast<const Derived*>(this)->m_particles;
        const auto best =
            std::max_element(particles.begin(), particles.end(), [](const auto& a, const auto& b) {
                return a.d->accumulated_log_w < b.d->accumulated_log_w;
            });
        return *best->d;
    }

  protected:
    unsigned m_threads = resolveThreadCount(0);  ///< setThreadCount()
};

}  // namespace mrpt_vslam::core
