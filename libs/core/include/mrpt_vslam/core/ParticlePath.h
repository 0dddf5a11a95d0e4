#pragma once

#include <mrpt_vslam/core/FixedSizePool.h>
#include <mrpt_vslam/core/Prefetch.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

namespace mrpt_vslam::core {

/** A particle's history in a particle filter over paths (FastSLAM): a `State` per step with its
 *  time. Steps are stored in chunks of kChunk, shared between the copies resampling makes, so a
 *  copy costs one pointer, not a path. A step goes into the chunk's next free slot: a chunk that
 *  several copies share takes the step of the first of them that adds one, the others start
 *  chunks of their own; so one step in kChunk allocates, not every step of every particle.
 *  Copies may add steps on different threads at the same time, but a path is not copied while
 *  it adds a step.
 *
 *  A path that holds its newest chunk alone (it started the chunk and was not copied since:
 *  between resamplings) adds a step without reading the chunk's count of used slots, which is
 *  far from the step's slot in memory; it writes that count when it is copied or lets go. */
template <class State>
class ParticlePath {
  public:
    struct TStep {
        double timestamp = 0;  ///< [s]
        State state;
    };
    static constexpr uint32_t kChunk = 8;

    ParticlePath() = default;
    ParticlePath(const ParticlePath& other)
        : m_chunk((other.publishUsed(), other.m_chunk)), m_count(other.m_count)
    {
    }
    ParticlePath(ParticlePath&& other) noexcept
        : m_chunk(std::move(other.m_chunk)),
          m_count(std::exchange(other.m_count, 0)),
          m_alone(other.m_alone.exchange(false, std::memory_order_relaxed))
    {
    }
    ParticlePath& operator=(const ParticlePath& other)
    {
        if (this == &other) return *this;
        publishUsed();
        other.publishUsed();
        m_chunk = other.m_chunk;
        m_count = other.m_count;
        return *this;
    }
    ParticlePath& operator=(ParticlePath&& other) noexcept
    {
        if (this == &other) return *this;
        publishUsed();
        m_chunk = std::move(other.m_chunk);
        m_count = std::exchange(other.m_count, 0);
        m_alone.store(other.m_alone.exchange(false, std::memory_order_relaxed),
                      std::memory_order_relaxed);
        return *this;
    }
    ~ParticlePath() { publishUsed(); }

    /// Adds a step whose state is built in place from `state_args`: `State{state_args...}`.
    template <class... StateArgs>
    void append(double t, StateArgs&&... state_args)
    {
        if (m_chunk && m_count < kChunk && claimSlot()) {
            try {
                new (m_chunk->slot(m_count))
                    TStep{t, State{std::forward<StateArgs>(state_args)...}};
            } catch (...) {
                if (!m_alone.load(std::memory_order_relaxed))
                    m_chunk->used.store(m_count, std::memory_order_relaxed);
                throw;
            }
            m_count++;
            return;
        }
        auto next = std::allocate_shared<Chunk>(PoolAllocator<Chunk>());
        new (next->slot(0)) TStep{t, State{std::forward<StateArgs>(state_args)...}};
        next->used.store(1, std::memory_order_relaxed);
        next->first = size();
        next->previous_count = m_count;
        publishUsed();
        next->previous = std::move(m_chunk);
        m_chunk = std::move(next);
        m_count = 1;
        m_alone.store(true, std::memory_order_relaxed);
    }

    /** Starts loading, for writing, the memory the next append() writes when it takes a slot of
     *  the newest chunk: a loop that appends to many paths calls it a few paths ahead, so that
     *  the misses of several paths overlap. Changes nothing. */
    void prefetchAppend() const
    {
        if (!m_chunk || m_count >= kChunk) return;
        Chunk* c = m_chunk.get();
        if (!m_alone.load(std::memory_order_relaxed)) prefetchObject(&c->used);
        prefetchObject(static_cast<const TStep*>(c->slot(m_count)));
    }

    size_t size() const { return m_chunk ? m_chunk->first + m_count : 0; }
    bool empty() const { return !m_chunk; }
    /// \pre !empty()
    const TStep& newest() const { return m_chunk->step(m_count - 1); }

    /// Calls f(step) for every step, newest first.
    template <class F>
    void forEachNewestFirst(F&& f) const
    {
        uint32_t n = m_count;
        for (const Chunk* c = m_chunk.get(); c; n = c->previous_count, c = c->previous.get())
            for (uint32_t i = n; i-- > 0;) f(c->step(i));
    }
    /// The steps, oldest first.
    std::vector<const TStep*> stepsOldestFirst() const
    {
        std::vector<const TStep*> steps(size());
        auto out = steps.rbegin();
        forEachNewestFirst([&](const TStep& s) { *out++ = &s; });
        return steps;
    }

  private:
    /// Takes slot m_count of m_chunk if no path through the chunk has taken it.
    bool claimSlot()
    {
        if (m_alone.load(std::memory_order_relaxed)) return true;
        uint32_t expected = m_count;
        return m_chunk->used.compare_exchange_strong(expected, m_count + 1,
                                                     std::memory_order_relaxed);
    }
    /// Writes the chunk's count of used slots if this path held the chunk alone: before
    /// another path may add to the chunk, or this one lets go of it.
    void publishUsed() const
    {
        if (m_alone.exchange(false, std::memory_order_relaxed))
            m_chunk->used.store(m_count, std::memory_order_relaxed);
    }

    struct Chunk {
        std::shared_ptr<Chunk> previous;
        uint32_t previous_count = 0;    ///< steps of `previous` on the paths through this chunk
        size_t first = 0;               ///< steps before this chunk
        std::atomic<uint32_t> used{0};  ///< slots holding a step (of any path through here)
        alignas(TStep) unsigned char slots[kChunk * sizeof(TStep)];

        Chunk() = default;
        Chunk(const Chunk&) = delete;
        Chunk& operator=(const Chunk&) = delete;
        void* slot(uint32_t i) { return slots + i * sizeof(TStep); }
        const TStep& step(uint32_t i) const
        {
            return *std::launder(reinterpret_cast<const TStep*>(slots + i * sizeof(TStep)));
        }
        /// Releases a chain of chunks nobody else holds iteratively (a long run would otherwise
        /// recurse once per chunk).
        ~Chunk()
        {
            for (uint32_t i = 0, n = used.load(std::memory_order_relaxed); i < n; i++)
                std::launder(reinterpret_cast<TStep*>(slot(i)))->~TStep();
            std::shared_ptr<Chunk> p = std::move(previous);
            while (p && p.use_count() == 1) {
                std::shared_ptr<Chunk> next = std::move(p->previous);
                p = std::move(next);  // the old chunk dies with an empty `previous`
            }
        }
    };
    std::shared_ptr<Chunk> m_chunk;
    uint32_t m_count = 0;  ///< steps of m_chunk on this path
    /// This path started m_chunk and was not copied since; the chunk's `used` may lag m_count.
    mutable std::atomic<bool> m_alone{false};
};

}  // namespace mrpt_vslam::core
