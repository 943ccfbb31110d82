#include "renderer/frame_memory.h"

#include <stdexcept>
#include <string>
#include <type_traits>

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

// Whether `id` lives in Frame::Scratch's own buffers; with `release`, frees them.
bool inScratch(Frame& f, Res id, bool release) {
    Frame::Scratch& s = f.scratch;
    const auto free = [release](auto& p) {
        if (release) p = std::decay_t<decltype(p)>();
        return true;
    };
    switch (id) {
        case Res::ShadowMap: return free(s.shadow.depth);
        case Res::VisibilityDepth: return free(s.visibility.depth);
        case Res::VisibilityIds: return free(s.visibility.ids);
        case Res::BackDepth: return free(s.backVisibility.depth);
        case Res::BackIds: return free(s.backVisibility.ids);
        case Res::BackZ: return free(s.backZ);
        case Res::HiZ:
            for (PlaneF& level : s.hiz.minZ) free(level);
            return true;
        default: return false;
    }
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

FrameMemory::FrameMemory(const CompiledGraph& graph, Frame& frame, bool forTruth)
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
        const int from = int(graph.passes[r.first].decl - first);
        const int to = int(graph.passes[r.last].decl - first);
        const bool transient = r.lifetime == Lifetime::Transient;
        if (inScratch(frame, r.id, false)) {
            if (transient && !forTruth) held_.push_back({r.id, from, to, true, true, true});
            continue;
        }
        if (framePlanes(frame, r.id).empty()) continue;
        held_.push_back({r.id, from, to, transient && !(forTruth && part(r.id)), false});
    }
}

void FrameMemory::take(int through) {
    for (Held& r : held_) {
        if (r.taken || r.first > through) continue;  // (scratch: its pass sizes its own)
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
        if (r.scratch) inScratch(frame_, r.id, true);
        for (PlaneF* p : framePlanes(frame_, r.id)) frame_.scratch.pool.give(*p);
        r.given = true;
    }
}

}  // namespace ssrt
