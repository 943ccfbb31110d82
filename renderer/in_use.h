// Whether a render call is using an object (a Frame, a FrameHistory): two calls handed the same
// one at once would race on its planes, so the second is refused with a clear error instead
// (Renderer::render claims both for the length of the call).
#pragma once

#include <atomic>

namespace ssrt {

class InUse {
public:
    InUse() = default;
    // A copy, or an object moved into, is another object: free, whatever the source's state.
    InUse(const InUse&) noexcept {}
    InUse& operator=(const InUse&) noexcept { return *this; }

    // Claims it; false when another call holds it (then nothing changes).
    bool claim() noexcept { return !held_.exchange(true, std::memory_order_acquire); }
    void release() noexcept { held_.store(false, std::memory_order_release); }
    // Whether a call holds it now (a moment later it may not).
    bool held() const noexcept { return held_.load(std::memory_order_acquire); }

private:
    std::atomic<bool> held_{false};
};

}  // namespace ssrt
