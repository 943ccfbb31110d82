// Planes that a frame's passes hand on to one another. A group of scratch planes that is dead
// until its pass runs again gives them back; a group about to be written takes planes of its
// size from here before anything is allocated. So the SSR trace's rays and march results and
// the denoiser's scratch, never alive at once, share one set of memory, in a sequence (no
// allocation once the first frame has run) and in a single frame (fewer fresh pages to fault
// in). (Filament's FrameGraph aliases transient resources so; here the passes say it.)
//
// Planes of two element types are pooled: f32 (PlaneF) and 16-bit (PlaneU16: the denoiser's
// f16 signals). A take that finds no free plane of its type and size, but a plane of the other
// type at that size whose memory block holds it, takes that block (Plane::reuse: an f16 plane
// in an f32 plane's block, which goes back to an f32 plane when one asks), so blocks change
// hands without going back to the allocator: a sequence allocates in its first frame only, and
// its memory does not fragment. (An f16 plane so made holds a whole f32 block: only f16 planes
// allocated new take half.)
//
// A plane taken holds whatever its last user left (finite values: every pass writes every
// pixel of the planes it takes before it reads them), as a plane kept across frames does.
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

#include "core/plane_table.h"

namespace ssrt {

class PlanePool {
public:
    // `p` at width x height: kept when it is, else a pooled plane of that size, else a new one.
    void take(PlaneF& p, int width, int height);
    void take(PlaneU16& p, int width, int height);
    template <class Group>
    void take(PlaneTable<Group>& group, int width, int height) {
        group.forEachPlane([&](std::string_view, auto& p) { take(p, width, height); });
    }
    // Moves `p` (when it holds memory) into the pool, leaving it empty.
    void give(PlaneF& p);
    void give(PlaneU16& p);
    template <class Group>
    void give(PlaneTable<Group>& group) {
        group.forEachPlane([&](std::string_view, auto& p) { give(p); });
    }
    // Frees the pooled planes of any other size (the frame's size changed).
    void keepOnly(int width, int height, int halfWidth, int halfHeight);
    std::size_t bytes() const;
    std::size_t size() const { return f32_.size() + f16_.size(); }

private:
    template <class T, class U>
    static void takeFrom(Plane<T>& p, std::vector<Plane<T>>& same, std::vector<Plane<U>>& other,
                         int width, int height);
    template <class T>
    static void giveTo(Plane<T>& p, std::vector<Plane<T>>& free);

    std::vector<PlaneF> f32_;
    std::vector<PlaneU16> f16_;
};

}  // namespace ssrt
