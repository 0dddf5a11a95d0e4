#include <mrpt_vslam/core/FixedSizePool.h>
#include <mrpt_vslam/multirobot/LandmarkStore.h>

#include <atomic>
#include <cassert>

namespace mrpt_vslam::multirobot {

LandmarkStore::Block& LandmarkStore::writableBlock(size_t b)
{
    if (b >= m_blocks.size()) m_blocks.resize(b + 1);
    auto& block = m_blocks[b];
    if (!block)
        block = std::allocate_shared<Block>(core::PoolAllocator<Block>());
    else if (block.use_count() > 1)
        block = std::allocate_shared<Block>(core::PoolAllocator<Block>(), *block);  // copy on write
    else  // sole owner; a particle updated on another thread may have just let go of it
        std::atomic_thread_fence(std::memory_order_acquire);
    return *block;
}

LandmarkStore& LandmarkStore::operator=(const LandmarkStore& other)
{
    m_blocks.resize(other.m_blocks.size());
    for (size_t b = 0; b < m_blocks.size(); b++)
        if (m_blocks[b] != other.m_blocks[b]) m_blocks[b] = other.m_blocks[b];
    m_count = other.m_count;
    return *this;
}

TVisualLandmark& LandmarkStore::modify(uint32_t id)
{
    assert(find(id));
    return writableBlock(id / kBlockSize).items[id % kBlockSize];
}

void LandmarkStore::insert(uint32_t id, const TVisualLandmark& landmark)
{
    Block& block = writableBlock(id / kBlockSize);
    const uint32_t bit = 1u << (id % kBlockSize);
    if (!(block.present & bit)) m_count++;
    block.present |= bit;
    block.items[id % kBlockSize] = landmark;
}

void LandmarkStore::erase(uint32_t id)
{
    if (!find(id)) return;
    writableBlock(id / kBlockSize).present &= ~(1u << (id % kBlockSize));
    m_count--;
}

void LandmarkStore::clear()
{
    m_blocks.clear();
    m_count = 0;
}

size_t LandmarkStore::unsharedBlocks() const
{
    size_t n = 0;
    for (const auto& b : m_blocks) n += (b && b.use_count() == 1) ? 1 : 0;
    return n;
}

}  // namespace mrpt_vslam::multirobot
