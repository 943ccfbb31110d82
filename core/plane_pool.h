// Planes that a frame's passes hand on to one another. A group of scratch planes that is dead
// until its pass runs again gives them back; a group about to be written takes planes of its
// size from here before anything is allocated. So the SSR trace's rays and march results and
// the denoiser's scratch, never alive at once, share one set of memory, in a sequence (no
// allocation once the first frame has run) and in a single frame (fewer fresh pages to fault
// in). (Filament's FrameGraph aliases transient resources so; here the passes say it.)
//
// A plane taken holds whatever its last user left (finite values: every pass writes every
// pixel of the planes it takes before it reads them), as a plane kept across frames does.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include "core/plane_table.h"

namespace ssrt {

class PlanePool {
public:
    // `p` at width x height: kept when it is, else a pooled plane of that size, else a new one.
    void take(PlaneF& p, int width, int height);
    template <class Group>
    void take(PlaneTable<Group>& group, int width, int height) {
        group.forEachPlane([&](std::string_view, PlaneF& p) { take(p, width, height); });
    }
    // Moves `p` (when it holds memory) into the pool, leaving it empty.
    void give(PlaneF& p);
    template <class Group>
    void give(PlaneTable<Group>& group) {
        group.forEachPlane([&](std::string_view, PlaneF& p) { give(p); });
    }
    // Fills every plane given back from now on with `value` (a NaN: a pass that reads a plane
    // after its memory went back, or before it wrote it, spreads the NaN to the image; the
    // frame graph's tests render so); nullopt: planes keep what they hold.
    void poison(std::optional<float> value) { poison_ = value; }
    // Frees the pooled planes of any other size (the frame's size changed).
    void keepOnly(int width, int height, int halfWidth, int halfHeight);
    std::size_t bytes() const;
    std::size_t size() const { return free_.size(); }

private:
    std::vector<PlaneF> free_;
    std::optional<float> poison_;
};

}  // namespace ssrt
