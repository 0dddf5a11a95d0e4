#include <gtest/gtest.h>
#include <mrpt_vslam/core/FixedSizePool.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <set>
#include <thread>
#include <vector>

using mrpt_vslam::core::FixedSizePool;
using mrpt_vslam::core::PoolAllocator;

// Every slot aligned, none overlapping another (each keeps the bytes written to it).
TEST(FixedSizePool, SlotsAreAlignedAndDisjoint)
{
    using Pool = FixedSizePool<40, 32>;
    std::vector<unsigned char*> slots;
    for (int i = 0; i < 500; i++) {
        auto* s = static_cast<unsigned char*>(Pool::allocate());
        EXPECT_EQ(reinterpret_cast<uintptr_t>(s) % 32, 0u);
        std::memset(s, i % 251, 40);
        slots.push_back(s);
    }
    for (size_t i = 0; i < slots.size(); i++)
        for (size_t b = 0; b < 40; b++) ASSERT_EQ(slots[i][b], i % 251) << "slot " << i;
    for (auto* s : slots) Pool::deallocate(s);
}

#if !defined(__SANITIZE_ADDRESS__)
// A freed slot is the next one handed out on the same thread.
TEST(FixedSizePool, FreedSlotsAreReused)
{
    using Pool = FixedSizePool<24, 8>;
    std::set<void*> first;
    for (int i = 0; i < 100; i++) first.insert(Pool::allocate());
    for (void* s : first) Pool::deallocate(s);
    std::set<void*> second;
    for (int i = 0; i < 100; i++) second.insert(Pool::allocate());
    EXPECT_EQ(first, second);
    for (void* s : second) Pool::deallocate(s);
}

// Slots one thread allocates and another frees go back, batch by batch, to the thread that
// allocates next, instead of piling up on the one that frees.
TEST(FixedSizePool, SlotsFollowTheThreadThatAllocates)
{
    using Pool = FixedSizePool<56, 8>;
    constexpr size_t kSlots = 20 * Pool::kBatch;
    std::vector<void*> made;
    std::thread([&] {
        for (size_t i = 0; i < kSlots; i++) made.push_back(Pool::allocate());
    }).join();  // the thread hands back its unused slots as it ends
    const size_t shared_after_maker = Pool::sharedSlots();

    for (void* s : made) Pool::deallocate(s);
    const size_t shared_after_free = Pool::sharedSlots();
    EXPECT_GE(shared_after_free, shared_after_maker + kSlots - 3 * Pool::kBatch);

    std::set<void*> freed(made.begin(), made.end());
    size_t reused = 0;
    std::thread([&] {
        std::vector<void*> taken;
        for (size_t i = 0; i < kSlots / 2; i++) taken.push_back(Pool::allocate());
        for (void* s : taken) reused += freed.count(s);
    }).join();
    EXPECT_EQ(reused, kSlots / 2);  // no new memory while the shared list has slots
}
#endif

namespace {
struct Counted {
    static inline int alive = 0;
    double payload[5] = {};
    Counted() { alive++; }
    Counted(const Counted& o) : payload{o.payload[0]} { alive++; }
    ~Counted() { alive--; }
};
}  // namespace

// std::allocate_shared through PoolAllocator constructs and destroys like std::make_shared.
TEST(PoolAllocator, AllocateSharedConstructsAndDestroys)
{
    {
        std::vector<std::shared_ptr<Counted>> objects;
        for (int i = 0; i < 300; i++) {
            objects.push_back(std::allocate_shared<Counted>(PoolAllocator<Counted>()));
            objects.back()->payload[0] = i;
        }
        EXPECT_EQ(Counted::alive, 300);
        auto copy = std::allocate_shared<Counted>(PoolAllocator<Counted>(), *objects[7]);
        EXPECT_EQ(copy->payload[0], 7);
        EXPECT_EQ(Counted::alive, 301);
    }
    EXPECT_EQ(Counted::alive, 0);
}
