// An allocator for std::vector whose storage starts on an `Align`-byte boundary (a cache
// line, say), which malloc does not promise for large blocks.
#pragma once

#include <cstddef>
#include <new>

namespace ssrt {

template <class T, std::size_t Align>
struct AlignedAllocator {
    using value_type = T;
    static_assert(Align >= alignof(T) && (Align & (Align - 1)) == 0, "a power of two");

    AlignedAllocator() = default;
    template <class U>
    AlignedAllocator(const AlignedAllocator<U, Align>&) {}
    template <class U>
    struct rebind {
        using other = AlignedAllocator<U, Align>;
    };

    T* allocate(std::size_t n) {
        return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(Align)));
    }
    void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t(Align)); }

    friend bool operator==(const AlignedAllocator&, const AlignedAllocator&) { return true; }
};

}  // namespace ssrt
