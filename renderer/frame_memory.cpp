#include "renderer/frame_memory.h"

#include <stdexcept>
#include <string>

namespace ssrt {

namespace {

// Calls fn(name, plane) for every plane of the Frame's own groups.
template <class Fn>
void forEachFramePlane(Frame& f, Fn&& fn) {
    f.image.forEachPlane(fn);
    f.gbuffer.forEachPlane(fn);
    f.material.forEachPlane(fn);
    f.ids.forEachPlane(fn);
    f.direct.forEachPlane(fn);
    f.trace.ssr.forEachPlane(fn);
    f.trace.ssgi.forEachPlane(fn);
    f.trace.denoise.forEachPlane(fn);
}

bool isDirectPart(Frame& f, const PlaneF& p) {
    bool in = false;
    f.direct.forEachPlane([&](std::string_view, PlaneF& q) { in = in || &q == &p; });
    return in;
}

}  // namespace

std::vector<PlaneF*> framePlanes(Frame& frame, Res id) {
    std::vector<PlaneF*> out;
    forEachFramePlane(frame, [&](std::string_view name, PlaneF& p) {
        if (resourceOfChannel(name) == id) out.push_back(&p);
    });
    return out;
}

int FrameMemory::declIndex(std::string_view pass) {
    const std::vector<PassDecl>& decls = passDecls();
    for (std::size_t i = 0; i < decls.size(); ++i)
        if (decls[i].name == pass) return int(i);
    throw std::logic_error("frame memory: no pass is called '" + std::string(pass) + "'");
}

FrameMemory::FrameMemory(const CompiledGraph& graph, Frame& frame, bool keepParts)
    : graph_(graph), frame_(frame) {
    const int w = graph.width, h = graph.height;
    frame.width = w;
    frame.height = h;
    PlanePool& pool = frame.scratch.pool;
    forEachFramePlane(frame, [&](std::string_view, PlaneF& p) { pool.give(p); });
    pool.keepOnly(w, h, (w + 1) / 2, (h + 1) / 2);
    const PassDecl* first = passDecls().data();
    const auto part = [&](Res id) {
        std::vector<PlaneF*> planes = framePlanes(frame, id);
        return !planes.empty() && isDirectPart(frame, *planes[0]);
    };
    for (const GraphResource& r : graph.resources) {
        if (framePlanes(frame, r.id).empty()) continue;
        held_.push_back({r.id, int(graph.passes[r.first].decl - first),
                         int(graph.passes[r.last].decl - first),
                         r.lifetime == Lifetime::Transient && !(keepParts && part(r.id))});
    }
}

void FrameMemory::take(int through) {
    for (Held& r : held_) {
        if (r.taken || r.first > through) continue;
        if (r.first <= done_)
            throw std::logic_error("frame memory: '" + std::string(resourceDecl(r.id).name) +
                                   "' is first written by a pass no step ran");
        for (PlaneF* p : framePlanes(frame_, r.id))
            frame_.scratch.pool.take(*p, graph_.width, graph_.height);
        r.taken = true;
    }
}

void FrameMemory::give(int through) {
    for (Held& r : held_) {
        if (!r.transient || r.given || !r.taken || r.last > through) continue;
        for (PlaneF* p : framePlanes(frame_, r.id)) frame_.scratch.pool.give(*p);
        r.given = true;
    }
}

}  // namespace ssrt
