// Where a frame's passes take the planes they hand on to one another, and give them back when
// dead. A plane given back is freed: its memory goes back to the planes' range
// (core/plane_memory.h), which keeps its pages resident and hands them to the next plane of any
// size or element type, best fit. So the SSR trace's rays and march results, the denoiser's f16
// scratch and the half frame's planes, never alive at once, share memory by bytes, not by plane
// size. (Filament's FrameGraph aliases transient resources so; here the frame graph says when,
// renderer/frame_memory.h.)
//
// A plane taken holds whatever its memory's last user left (every pass writes every pixel of
// the planes it takes before it reads them), unless poisoned.
#pragma once

#include <optional>
#include <string_view>

#include "core/plane_table.h"

namespace ssrt {

class PlanePool {
public:
    // `p` at width x height: kept when it is, else newly allocated.
    void take(PlaneF& p, int width, int height);
    void take(PlaneU16& p, int width, int height);
    void take(PlaneU64& p, int width, int height);
    template <class Group>
    void take(PlaneTable<Group>& group, int width, int height) {
        group.forEachPlane([&](std::string_view, auto& p) { take(p, width, height); });
    }
    // Frees `p`, leaving it empty.
    void give(PlaneF& p);
    void give(PlaneU16& p);
    void give(PlaneU64& p);
    template <class Group>
    void give(PlaneTable<Group>& group) {
        group.forEachPlane([&](std::string_view, auto& p) { give(p); });
    }
    // Fills every plane taken from now on with `value` (a NaN: a pass that reads a plane before
    // it wrote it spreads the NaN to the image, and one that reads a plane after it was given
    // back finds it empty; the frame graph's tests render so); nullopt: planes keep what their
    // memory held.
    void poison(std::optional<float> value) { poison_ = value; }

private:
    std::optional<float> poison_;
};

}  // namespace ssrt
