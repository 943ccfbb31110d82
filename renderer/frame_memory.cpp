#include "renderer/frame_memory.h"

#include <array>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace ssrt {

namespace {

// A pyramid's levels and their packed copy.
bool freeHiZ(HiZPyramid& hiz, bool release) {
    if (release) hiz = HiZPyramid();
    return true;
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
        case Res::HiZ: return freeHiZ(s.hiz, release);
        case Res::ThinFeatures:
            for (PlaneF& p : s.thin.levels) free(p);
            return true;
        case Res::HalfGBuffer:
            GBufferPlanesF::forEach(
                s.half.frame, [&](GBufferPlane, PlaneF& p) { free(p); }, HalfFrame::kPlanes);
            return true;
        case Res::HalfHitLight:
            for (auto& p : s.half.frame.hitLight) free(p);
            return true;
        case Res::HalfBackZ: return free(s.half.frame.backZ);
        case Res::HalfIds: return free(s.half.frame.ids);
        case Res::HalfThinFeatures:
            for (PlaneF& p : s.half.thin.levels) free(p);
            return true;
        case Res::HalfGuides:
            GBufferPlanesF::forEach(
                s.half.frame.guide, [&](GBufferPlane, PlaneF& p) { free(p); },
                HalfFrame::kGuidePlanes);
            return true;
        case Res::HalfHiZ: return freeHiZ(s.half.hiz, release);
        case Res::HalfRayPdf: return free(s.half.rays.pdf);
        default: return false;
    }
}

}  // namespace

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
    // Every plane of the frame's groups back to the pool, each found under its resource (the
    // groups name their planes from the resource table; Res::Count, one past the table, for a
    // name it lacks), and the direct pass's parts marked.
    PlanePool& pool = frame.scratch.pool;
    std::array<std::vector<PlaneF*>, kResourceCount + 1> planes;
    std::array<std::vector<PlaneU16*>, kResourceCount + 1> planesU16;
    frame.forEachPlane([&](std::string_view name, auto& p) {
        pool.give(p);
        const std::size_t id = std::size_t(resourceOfChannel(name));
        if constexpr (std::is_same_v<std::decay_t<decltype(p)>, PlaneU16>)
            planesU16[id].push_back(&p);
        else planes[id].push_back(&p);
    });
    std::array<bool, kResourceCount + 1> part{};
    frame.direct.forEachPlane(
        [&](std::string_view name, auto&) { part[std::size_t(resourceOfChannel(name))] = true; });
    const PassDecl* first = passDecls().data();
    for (const GraphResource& r : graph.resources) {
        const std::size_t id = std::size_t(r.id);
        Held held{.id = r.id,
                  .first = int(graph.passes[r.first].decl - first),
                  .last = int(graph.passes[r.last].decl - first),
                  .transient = r.lifetime == Lifetime::Transient,
                  .planes = std::move(planes[id]),
                  .planesU16 = std::move(planesU16[id])};
        if (inScratch(frame, r.id, false)) {
            // (its pass sizes its own buffers: nothing to take)
            held.taken = true;
            if (held.transient && !forTruth) held_.push_back(std::move(held));
        } else if (!held.planes.empty() || !held.planesU16.empty()) {
            held.transient = held.transient && !(forTruth && part[id]);
            held_.push_back(std::move(held));
        }
    }
}

void FrameMemory::take(int through) {
    for (Held& r : held_) {
        if (r.taken || r.first > through) continue;
        if (r.first <= done_)
            throw std::logic_error("frame memory: '" + std::string(resourceDecl(r.id).name) +
                                   "' is first written by a pass no step ran");
        for (PlaneF* p : r.planes) frame_.scratch.pool.take(*p, graph_.width, graph_.height);
        for (PlaneU16* p : r.planesU16) frame_.scratch.pool.take(*p, graph_.width, graph_.height);
        r.taken = true;
    }
}

void FrameMemory::give(int through) {
    for (Held& r : held_) {
        if (!r.transient || r.given || !r.taken || r.last > through) continue;
        if (r.planes.empty() && r.planesU16.empty()) inScratch(frame_, r.id, true);
        for (PlaneF* p : r.planes) frame_.scratch.pool.give(*p);
        for (PlaneU16* p : r.planesU16) frame_.scratch.pool.give(*p);
        r.given = true;
    }
}

}  // namespace ssrt
