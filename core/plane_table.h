// A group of planes (of any element type: Plane<T>) that lists its members once: `table(group, fn)`
// calls fn(name, plane) for each, in file order. That one list gives the EXR channel names
// (renderer/frame.h), sizes and frees the group, and counts its bytes (the --stats memory table),
// so no other code repeats it. (After Filament's FrameHistoryEntry and NRD's resource enums: named
// resources, not strings looked up at each use.)
#pragma once

#include <cstddef>
#include <string_view>
#include <type_traits>

#include "core/image.h"

namespace ssrt {

template <class Group>
struct PlaneTable {
    template <class Fn>
    void forEachPlane(Fn&& fn) {
        Group::table(static_cast<Group&>(*this), fn);
    }
    template <class Fn>
    void forEachPlane(Fn&& fn) const {
        Group::table(static_cast<const Group&>(*this), fn);
    }
    // Every plane of the group at this size (kept when it already is), or all empty.
    void ensureSize(int width, int height) {
        forEachPlane([&](std::string_view, auto& p) { p.ensureSize(width, height); });
    }
    void release() {
        forEachPlane([](std::string_view, auto& p) { p = std::decay_t<decltype(p)>(); });
    }
    // What its planes hold, row padding included.
    std::size_t bytes() const {
        std::size_t n = 0;
        forEachPlane([&](std::string_view, const auto& p) { n += p.bytes(); });
        return n;
    }
};

}  // namespace ssrt
