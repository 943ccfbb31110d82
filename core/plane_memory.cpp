#include "core/plane_memory.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <mutex>
#include <new>

namespace ssrt {

namespace {

constexpr std::size_t kLine = 64, kPage = 4096, kHugePage = std::size_t(2) << 20;
// Address space, not memory: no page of it is backed until a plane touches it. 256 GiB holds
// a 16384x16384 frame's planes.
constexpr std::size_t kReserve = std::size_t(256) << 30;

// Kept in the cache line before every plane's first byte.
struct Header {
    unsigned char* block;    // where the block (or malloc's allocation) starts
    std::size_t blockBytes;  // 0: from malloc
};
static_assert(sizeof(Header) <= kLine);

// Sanitizers watch malloc's allocations for overruns; planes carved out of one mapping
// would hide them. Those builds (and a machine where the range cannot be reserved, such as
// one that forbids overcommitting) take planes from malloc.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kUseRange = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
constexpr bool kUseRange = false;
#else
constexpr bool kUseRange = true;
#endif
#else
constexpr bool kUseRange = true;
#endif

class Range {
public:
    Range() {
        if (!kUseRange) return;
        void* p = ::mmap(nullptr, kReserve + kHugePage, PROT_READ | PROT_WRITE,
                         MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
        if (p == MAP_FAILED) return;
        const auto at = reinterpret_cast<std::uintptr_t>(p);
        base_ = reinterpret_cast<unsigned char*>((at + kHugePage - 1) & ~(kHugePage - 1));
#ifdef MADV_HUGEPAGE
        ::madvise(base_, kReserve, MADV_HUGEPAGE);  // a kernel without huge pages ignores it
#endif
        free_[0] = kReserve;
    }

    bool reserved() const { return base_ != nullptr; }

    // Best fit: the smallest free block that holds `bytes`, the lowest of equals; nullptr
    // when none does.
    unsigned char* take(std::size_t bytes) {
        std::lock_guard lock(mutex_);
        auto best = free_.end();
        for (auto it = free_.begin(); it != free_.end(); ++it)
            if (it->second >= bytes && (best == free_.end() || it->second < best->second))
                best = it;
        if (best == free_.end()) return nullptr;
        const std::size_t start = best->first, left = best->second - bytes;
        free_.erase(best);
        if (left) free_[start + bytes] = left;
        inUse_ += bytes;
        top_ = std::max(top_, start + bytes);
        return base_ + start;
    }

    void give(unsigned char* block, std::size_t bytes) {
        std::lock_guard lock(mutex_);
        inUse_ -= bytes;
        std::size_t start = block - base_;
        auto next = free_.lower_bound(start);
        if (next != free_.begin()) {
            auto prev = std::prev(next);
            if (prev->first + prev->second == start) {
                start = prev->first;
                bytes += prev->second;
                free_.erase(prev);
            }
        }
        if (next != free_.end() && start + bytes == next->first) {
            bytes += next->second;
            free_.erase(next);
        }
        free_[start] = bytes;
    }

    PlaneMemoryUse use() {
        std::lock_guard lock(mutex_);
        return {inUse_, free_.size(), true, top_};
    }

private:
    unsigned char* base_ = nullptr;
    std::mutex mutex_;
    std::map<std::size_t, std::size_t> free_;  // offset -> bytes, in address order
    std::size_t inUse_ = 0;
    std::size_t top_ = 0;  // the highest end a block has had
};

// Never destroyed: planes in static objects may be freed after any other static's end.
Range& range() {
    static Range* r = new Range;
    return *r;
}

}  // namespace

void* allocatePlaneMemory(std::size_t bytes, std::size_t stagger) {
    const std::size_t total = kLine + stagger + bytes;
    Header header{nullptr, 0};
    if (range().reserved()) {
        header.blockBytes = (total + kPage - 1) & ~(kPage - 1);
        header.block = range().take(header.blockBytes);
        if (!header.block) header.blockBytes = 0;  // the range is full: malloc's turn
    }
    if (!header.block) {
        header.block = static_cast<unsigned char*>(
            std::aligned_alloc(kLine, (total + kLine - 1) & ~(kLine - 1)));
        if (!header.block) throw std::bad_alloc();
    }
    unsigned char* data = header.block + kLine + stagger;
    *reinterpret_cast<Header*>(data - kLine) = header;
    return data;
}

void freePlaneMemory(void* p) {
    if (!p) return;
    const Header header = *reinterpret_cast<const Header*>(static_cast<unsigned char*>(p) - kLine);
    if (header.blockBytes) range().give(header.block, header.blockBytes);
    else std::free(header.block);
}

PlaneMemoryUse planeMemoryUse() {
    if (!range().reserved()) return {};
    return range().use();
}

}  // namespace ssrt
