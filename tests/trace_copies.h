// Deep copies of a sample's rays and march result, kept by a TraceObserver until the frame
// that marched them is done (the renderer reuses their planes for the next sample).
#pragma once

#include <string_view>
#include <vector>

#include "trace/trace_types.h"

namespace ssrt::test {

// Every plane of a plane table cloned (RayBatch, MarchResult), the batch's corner kept.
template <class Table>
Table copyOf(const Table& from) {
    std::vector<const PlaneF*> planes;
    from.forEachPlane([&](std::string_view, const PlaneF& p) { planes.push_back(&p); });
    Table to;
    std::size_t i = 0;
    to.forEachPlane([&](std::string_view, PlaneF& p) { p = planes[i++]->clone(); });
    if constexpr (requires { to.corner; }) to.corner = from.corner;
    return to;
}

}  // namespace ssrt::test
