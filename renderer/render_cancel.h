// Stopping a frame part-way: FrameInput::cancel, a flag the caller raises from anywhere (a
// signal handler: the ssrt command's SIGINT), is read between the frame's passes, and a raised
// flag ends the render call with RenderCancelled. Between passes, not inside them, so that a
// pass never stops half-way through its tiles and no kernel checks a flag: the longest wait is
// one pass (about a tenth of a 1080p frame). Reading the flag changes nothing the frame
// computes, so a render that is not cancelled gives the same bits with or without one.
#pragma once

#include <atomic>
#include <stdexcept>

namespace ssrt {

// What a cancelled render throws. The frame and the history handed to it are left part-way:
// neither is to be read; a history is to be rendered again from a cut (resetHistory).
struct RenderCancelled : std::runtime_error {
    RenderCancelled() : std::runtime_error("the render was cancelled") {}
};

// Throws RenderCancelled when `cancel` is given and raised.
inline void stopIfCancelled(const std::atomic<bool>* cancel) {
    if (cancel && cancel->load(std::memory_order_relaxed)) throw RenderCancelled();
}

}  // namespace ssrt
