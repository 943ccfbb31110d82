// Where planes' memory comes from: one range of address space advised for transparent huge
// pages, handed out best fit, with freed blocks merged with their free neighbours.
//
// Why not malloc: a frame's first touch of fresh memory was a single image's largest cost
// (page faults and the kernel zeroing pages). Huge pages fault 2 MiB at a time, but the
// kernel grants one only where an aligned 2 MiB stretch lies inside one advised mapping, and
// malloc gives each large plane a mapping of its own: at 1280x720 (3.7 MB float planes, 0.9
// MB half planes) only 37 % of a frame's memory got huge pages. In one advised range, planes
// side by side share huge pages across their borders.
#pragma once

#include <cstddef>

namespace ssrt {

// At least `bytes`, starting `stagger` bytes (a multiple of 64) past a 64-byte boundary, so
// that large planes can start at different cache sets (core/image.cpp). Throws
// std::bad_alloc.
void* allocatePlaneMemory(std::size_t bytes, std::size_t stagger);
void freePlaneMemory(void* p);

// What the range holds now: the bytes handed out, the free blocks' count, and the bytes below
// the highest end any block has had: the range's resident memory, as freed blocks keep their
// pages (all 0 where planes come from malloc: a sanitizer's build, or no range could be
// reserved).
struct PlaneMemoryUse {
    std::size_t bytesInUse = 0;
    std::size_t freeBlocks = 0;
    bool fromRange = false;
    std::size_t bytesTouched = 0;
};
PlaneMemoryUse planeMemoryUse();

// An allocator for std::vector whose storage comes from the planes' range (64-byte aligned), for
// a frame's buffers that are not planes (the Hi-Z pyramid's packed copy): freed each frame
// after its last pass, its pages stay resident for the next frame's, as a plane's do, instead
// of going back to the kernel and faulting in again.
template <class T>
struct PlaneMemoryAllocator {
    using value_type = T;
    PlaneMemoryAllocator() = default;
    template <class U>
    PlaneMemoryAllocator(const PlaneMemoryAllocator<U>&) {}
    T* allocate(std::size_t n) { return static_cast<T*>(allocatePlaneMemory(n * sizeof(T), 0)); }
    void deallocate(T* p, std::size_t) { freePlaneMemory(p); }
    friend bool operator==(const PlaneMemoryAllocator&, const PlaneMemoryAllocator&) {
        return true;
    }
};

}  // namespace ssrt
