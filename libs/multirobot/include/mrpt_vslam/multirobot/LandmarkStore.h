#pragma once

#include <mrpt_vslam/core/Prefetch.h>
#include <mrpt_vslam/multirobot/VisualLandmark.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace mrpt_vslam::multirobot {

/** The landmarks of one particle, indexed by landmark id, with copy-on-write storage shared
 *  between particles.
 *
 *  Ids are dense and grow with time (LandmarkDescriptorPool hands them out), so the store is a
 *  vector of fixed-size blocks of consecutive ids. Copying a store (resampling duplicates a
 *  particle) copies only the block pointers; the first write to a block that another store
 *  also holds clones that block. Landmarks measured together were mostly created together, so
 *  one step touches few blocks: the cost of a step grows with the measurements, not with the
 *  map size, and M particles share every block none of them changed since they split. */
class LandmarkStore {
  public:
    static constexpr uint32_t kBlockSize = 16;

    LandmarkStore() = default;
    LandmarkStore(const LandmarkStore&) = default;
    LandmarkStore(LandmarkStore&&) = default;
    LandmarkStore& operator=(LandmarkStore&&) = default;
    /// Holds other's blocks; one both hold already is not touched (resampling assigns a copy
    /// of a particle to a relative's store, which shares most of its blocks).
    LandmarkStore& operator=(const LandmarkStore& other);

    /// The landmark with this id, or nullptr if this particle has none.
    const TVisualLandmark* find(uint32_t id) const
    {
        const size_t b = id / kBlockSize;
        if (b >= m_blocks.size() || !m_blocks[b]) return nullptr;
        const Block& block = *m_blocks[b];
        const uint32_t bit = 1u << (id % kBlockSize);
        return (block.present & bit) ? &block.items[id % kBlockSize] : nullptr;
    }
    /// Starts reading the table itself (where its entries are), before prefetchEntry().
    void prefetchTable() const { core::prefetchObject(&m_blocks); }
    /** Starts reading what find(id) reads, in two stages a few look-ups apart so that the
     *  misses overlap: first the entry of id's block in the table (prefetchEntry()), then, once
     *  that entry is in the cache, the block's presence bits and the landmark
     *  (prefetchLandmark()). */
    void prefetchEntry(uint32_t id) const
    {
        const size_t b = id / kBlockSize;
        if (b < m_blocks.size()) core::prefetchObject(&m_blocks[b]);
    }
    void prefetchLandmark(uint32_t id) const
    {
        const size_t b = id / kBlockSize;
        if (b >= m_blocks.size() || !m_blocks[b]) return;
        const Block& block = *m_blocks[b];
        core::prefetchObject(&block.present);
        core::prefetchObject(&block.items[id % kBlockSize]);
    }
    /// Writable access to an existing landmark (clones its block if shared). \pre find(id)
    TVisualLandmark& modify(uint32_t id);
    /// Adds (or replaces) the landmark `id`.
    void insert(uint32_t id, const TVisualLandmark& landmark);
    /// Removes the landmark `id` if this store holds it.
    void erase(uint32_t id);
    /// Removes every landmark.
    void clear();

    size_t size() const { return m_count; }
    bool empty() const { return m_count == 0; }
    /// Calls f(id, landmark) for every landmark, in increasing id order.
    template <class F>
    void forEach(F&& f) const
    {
        for (size_t b = 0; b < m_blocks.size(); b++) {
            if (!m_blocks[b]) continue;
            for (uint32_t i = 0; i < kBlockSize; i++)
                if (m_blocks[b]->present & (1u << i))
                    f(static_cast<uint32_t>(b * kBlockSize + i), m_blocks[b]->items[i]);
        }
    }
    /** ORs this store's ids into `held`, a bit set of ids (bit id % 32 of word id / 32; the
     *  set grows to cover every id held). */
    void addIdsTo(std::vector<uint32_t>& held) const
    {
        static_assert(32 % kBlockSize == 0, "whole blocks per word of `held`");
        constexpr size_t kPerWord = 32 / kBlockSize;
        const size_t words = (m_blocks.size() + kPerWord - 1) / kPerWord;
        if (held.size() < words) held.resize(words, 0);
        for (size_t b = 0; b < m_blocks.size(); b++)
            if (m_blocks[b])
                held[b / kPerWord] |= m_blocks[b]->present << (b % kPerWord * kBlockSize);
    }
    /// Blocks this store holds alone (not shared with any copy): for tests and statistics.
    size_t unsharedBlocks() const;

  private:
    struct Block {
        std::array<TVisualLandmark, kBlockSize> items;
        uint32_t present = 0;  ///< bit i: items[i] holds a landmark
    };
    Block& writableBlock(size_t b);

    std::vector<std::shared_ptr<Block>> m_blocks;
    size_t m_count = 0;
};

}  // namespace mrpt_vslam::multirobot
