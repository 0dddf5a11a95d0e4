#pragma once

#include <mrpt/bayes/CParticleFilterData.h>
#include <mrpt_vslam/core/ParallelFor.h>
#include <mrpt_vslam/core/Prefetch.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace mrpt_vslam::core {

/** mrpt::bayes::CParticleFilterDataImpl whose resampling leaves equal weights, and which knows
 *  each particle's accumulated log-weight (the particle data's `accumulated_log_w`).
 *
 *  MRPT 2.5's CParticleFilterCapable::performResampling(options) resets the log-weights of only
 *  `out_particle_count` particles, 0 by default, which is how CParticleFilter::executeOn calls
 *  it: the resampled copies keep their parents' weights, so every later step weighs the set by
 *  its old weights a second time. Resampling always goes through performSubstitution(), so this
 *  class sets every log-weight to 0 there. It reaches the particles by static_cast where MRPT
 *  2.5's CRTP helper dynamic_casts on every access (twice per particle in ESS(), which the
 *  filters call after each robot, and in normalizeWeights()). Use it in place of
 *  CParticleFilterDataImpl; derived filters run their per-particle loops on m_threads. */
template <class Derived, class ParticleList>
class ParticleFilterDataImpl : public mrpt::bayes::CParticleFilterDataImpl<Derived, ParticleList> {
  public:
    /// Threads the particles are updated on (0, the default: every core). The
    /// results do not depend on it: the same seed gives the same particles bit for bit.
    void setThreadCount(unsigned threads) { m_threads = resolveThreadCount(threads); }

    /** MRPT's new set (the particles `indx` draws, in increasing index, the first draw of a
     *  particle taking its data, the others copies), with every log-weight 0, and the copies
     *  made into the data of particles nobody drew (assigned, not allocated and freed). */
    void performSubstitution(const std::vector<size_t>& indx) override
    {
        ParticleList& old = particles();
        std::vector<size_t> sorted(indx);
        std::sort(sorted.begin(), sorted.end());
        std::vector<size_t> first(old.size(), kNone);  // new index of an old particle's data
        for (size_t i = 0; i < sorted.size(); i++)
            if (first[sorted[i]] == kNone) first[sorted[i]] = i;
        std::vector<size_t> spare;  // particles nobody drew, in increasing index
        for (size_t j = 0; j < old.size(); j++)
            if (first[j] == kNone) spare.push_back(j);
        ParticleList drawn(sorted.size());
        size_t next_spare = 0;
        for (size_t i = 0; i < sorted.size(); i++) {
            const size_t j = sorted[i];
            if (first[j] == i)
                drawn[i].d = std::move(old[j].d);
            else if (next_spare < spare.size())
                drawn[i].d = std::move(old[spare[next_spare++]].d);
            drawn[i].log_w = 0;
        }
        // the copies, each made where the loops over the particles update it (a share of the
        // new indices per thread); they read only first draws, which none of them writes
        // (bound by memory: the objects of this thread's copy kCopyAhead indices on requested)
        parallelForAhead(sorted.size(), m_threads, [&](size_t i, size_t end) {
            if (const size_t a = i + kCopyAhead; a < end && first[sorted[a]] != a) {
                prefetchObject(drawn[a].d.get());
                prefetchObject(drawn[first[sorted[a]]].d.get());
            }
            if (first[sorted[i]] == i) return;
            const auto& source = drawn[first[sorted[i]]].d;
            if (drawn[i].d.get())
                *drawn[i].d = *source;
            else
                drawn[i].d = source;  // a deep copy
        });
        old = std::move(drawn);
    }

    /// Subtracts the largest log-weight from all; returns max / min weight: MRPT's.
    double normalizeWeights(double* out_max_log_w = nullptr) override
    {
        if (particles().empty()) return 0;
        double min_w = particles().front().log_w, max_w = min_w;
        for (const auto& p : particles()) {
            max_w = std::max(max_w, p.log_w);
            min_w = std::min(min_w, p.log_w);
        }
        for (auto& p : particles()) p.log_w -= max_w;
        if (out_max_log_w) *out_max_log_w = max_w;
        return std::exp(max_w - min_w);
    }

    /// N_eff = 1 / (M Σ w̃ᵢ²), w̃ the normalized weights: MRPT's, to the last bit.
    double ESS() const override
    {
        const ParticleList& all = particles();
        std::vector<double> w(all.size());  // the exponentials on the threads, sums in order
        parallelFor(w.size(), m_threads, [&](size_t i) { w[i] = std::exp(all[i].log_w); });
        double sum = 0;
        for (const double wi : w) sum += wi;
        double cum = 0;
        for (const double wi : w) cum += (wi / sum) * (wi / sum);
        return cum == 0 ? 0 : 1.0 / (static_cast<double>(w.size()) * cum);
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
        const auto best = std::max_element(
            particles().begin(), particles().end(), [](const auto& a, const auto& b) {
                return a.d->accumulated_log_w < b.d->accumulated_log_w;
            });
        return *best->d;
    }

  protected:
    static constexpr size_t kNone = static_cast<size_t>(-1);
    static constexpr size_t kCopyAhead = 2;
    ParticleList& particles() { return static_cast<Derived*>(this)->m_particles; }
    const ParticleList& particles() const { return static_cast<const Derived*>(this)->m_particles; }

    unsigned m_threads = resolveThreadCount(0);  ///< setThreadCount()
};

}  // namespace mrpt_vslam::core
