#pragma once

#include <mrpt_vslam/core/Prefetch.h>

#include <cstddef>
#include <mutex>
#include <new>
#include <vector>

namespace mrpt_vslam::core {

/** Memory for objects of one size that a particle filter allocates and frees by the thousand
 *  each step, from several threads: the copy-on-write landmark blocks and path chunks of its
 *  particles (created on the filter's threads, released by resampling on the caller's).
 *
 *  Each thread keeps a free list of `Size`-byte slots. A thread that has freed more than two
 *  batches beyond what it uses hands one batch to a shared list, where a thread that runs dry
 *  takes it (one lock per kBatch slots), so memory follows the work instead of piling up on the
 *  thread that frees. Slots come from slabs of kBatch slots that stay in the process until exit.
 *  Under AddressSanitizer every slot is a plain allocation, so its checks still see each one. */
template <size_t Size, size_t Align>
class FixedSizePool {
  public:
    static constexpr size_t kBatch = 64;

    static void* allocate()
    {
#if defined(__SANITIZE_ADDRESS__)
        return ::operator new(kSlot, std::align_val_t(kAlign));
#else
        Local& local = t_local;
        if (!local.head) local.take(shared());
        Slot* s = local.head;
        local.head = s->next;
        local.count--;
        // the next allocation reads the next slot's link: a slot freed long ago is not cached
        prefetchObject(local.head);
        return s;
#endif
    }

    static void deallocate(void* p) noexcept
    {
#if defined(__SANITIZE_ADDRESS__)
        ::operator delete(p, std::align_val_t(kAlign));
#else
        Local& local = t_local;
        auto* s = static_cast<Slot*>(p);
        s->next = local.head;
        local.head = s;
        if (++local.count >= 3 * kBatch) local.give(shared(), kBatch);
#endif
    }

    /// Slots in the shared list (for tests).
    static size_t sharedSlots()
    {
        Shared& sh = shared();
        const std::lock_guard<std::mutex> lock(sh.mutex);
        size_t n = 0;
        for (const auto& b : sh.batches) n += b.count;
        return n;
    }

  private:
    struct Slot {
        Slot* next;
    };
    static constexpr size_t kAlign = Align > alignof(Slot) ? Align : alignof(Slot);
    static constexpr size_t kSlot =
        ((Size > sizeof(Slot) ? Size : sizeof(Slot)) + kAlign - 1) / kAlign * kAlign;

    struct Batch {
        Slot* head;
        size_t count;
    };
    struct Shared {
        std::mutex mutex;
        std::vector<Batch> batches;
    };
    /// Never destroyed: threads that end after static destruction still hand their slots back.
    static Shared& shared()
    {
        static Shared* const s = new Shared;
        return *s;
    }

    struct Local {
        Slot* head = nullptr;
        size_t count = 0;

        /// A batch from the shared list, or a new slab.
        void take(Shared& sh)
        {
            {
                const std::lock_guard<std::mutex> lock(sh.mutex);
                if (!sh.batches.empty()) {
                    head = sh.batches.back().head;
                    count = sh.batches.back().count;
                    sh.batches.pop_back();
                    return;
                }
            }
            auto* slab =
                static_cast<std::byte*>(::operator new(kSlot* kBatch, std::align_val_t(kAlign)));
            for (size_t i = kBatch; i-- > 0;) {
                auto* s = reinterpret_cast<Slot*>(slab + i * kSlot);
                s->next = head;
                head = s;
            }
            count = kBatch;
        }
        /// The first n slots of the list to the shared list.
        void give(Shared& sh, size_t n)
        {
            Slot* first = head;
            Slot* last = head;
            for (size_t i = 1; i < n; i++) last = last->next;
            head = last->next;
            last->next = nullptr;
            count -= n;
            const std::lock_guard<std::mutex> lock(sh.mutex);
            sh.batches.push_back({first, n});
        }
        ~Local()
        {
            if (head) give(shared(), count);
        }
    };
    static inline thread_local Local t_local;
};

/** A standard allocator of single objects from FixedSizePool, for std::allocate_shared. */
template <class T>
struct PoolAllocator {
    using value_type = T;

    PoolAllocator() = default;
    template <class U>
    PoolAllocator(const PoolAllocator<U>&) noexcept
    {
    }

    T* allocate(size_t n)
    {
        if (n != 1) throw std::bad_alloc();  // allocate_shared asks for one object
        return static_cast<T*>(FixedSizePool<sizeof(T), alignof(T)>::allocate());
    }
    void deallocate(T* p, size_t) noexcept { FixedSizePool<sizeof(T), alignof(T)>::deallocate(p); }

    template <class U>
    bool operator==(const PoolAllocator<U>&) const noexcept
    {
        return true;
    }
    template <class U>
    bool operator!=(const PoolAllocator<U>&) const noexcept
    {
        return false;
    }
};

}  // namespace mrpt_vslam::core
