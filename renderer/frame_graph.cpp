#include "renderer/frame_graph.h"

#include <algorithm>
#include <array>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/tiles.h"
#include "renderer/direct_lighting.h"
#include "renderer/resolve_tables.h"
#include "trace/tile_chain.h"

namespace ssrt {

namespace {

// Texels of one channel at a resolution.
std::size_t texels(Resolution r, int w, int h, int shadowMapSize) {
    const auto pyramid = [](std::size_t x, std::size_t y) {
        std::size_t n = 0;
        for (;;) {
            n += x * y;
            if (x == 1 && y == 1) return n;
            x = (x + 1) / 2, y = (y + 1) / 2;
        }
    };
    const std::size_t hw = std::size_t(w + 1) / 2, hh = std::size_t(h + 1) / 2;
    switch (r) {
        case Resolution::Full: return std::size_t(w) * std::size_t(h);
        case Resolution::Half: return hw * hh;
        case Resolution::ShadowMap: return std::size_t(shadowMapSize) * std::size_t(shadowMapSize);
        case Resolution::Pyramid: return pyramid(std::size_t(w), std::size_t(h));
        case Resolution::HalfPyramid: return pyramid(hw, hh);
        case Resolution::TileRing:
            return std::size_t(w) * std::size_t(std::min(h, kChainRingTileRows * kTileSize));
    }
    return 0;
}

// Planes a resource takes (a unit vector's three channels share one plane of oct16).
int planesOf(const ResourceDecl& d) {
    return d.format == PixelFormat::OctSnorm16 ? (d.channelCount() + 2) / 3 : d.channelCount();
}

std::size_t resourceBytes(const ResourceDecl& d, int w, int h, int shadowMapSize) {
    const std::size_t n = texels(d.resolution, w, h, shadowMapSize);
    return n * std::size_t(bytesPerTexel(d.format)) * std::size_t(planesOf(d));
}

bool holds(GraphCondition c, const GraphKey& k) { return c == nullptr || c(k); }

std::vector<Access> kept(const std::vector<Access>& list, const GraphKey& k) {
    std::vector<Access> out;
    for (const Access& a : list)
        if (holds(a.when, k) &&
            std::none_of(out.begin(), out.end(), [&](const Access& b) { return b.res == a.res; }))
            out.push_back(a);
    return out;
}

bool contains(const std::vector<Access>& list, Res r) {
    return std::any_of(list.begin(), list.end(), [&](const Access& a) { return a.res == r; });
}

// Whether a resource outlives the frame: history, and outputs the settings hand out.
bool isRoot(const ResourceDecl& d, const GraphKey& k) {
    return d.lifetime == Lifetime::History ||
           (d.lifetime == Lifetime::Output && holds(d.handedOut, k));
}

// Culls, back to front: a pass is kept when it writes something that is a root or read by a
// kept pass after it; writes nothing needs are dropped. A write that does not read the
// resource ends the need for it (the value before is overwritten).
void cull(const GraphKey& k, std::vector<GraphPass>& passes,
          std::vector<std::string_view>& culled) {
    std::array<bool, kResourceCount> needed{};
    for (int r = 0; r < kResourceCount; ++r) needed[r] = isRoot(resourceDecl(Res(r)), k);
    std::vector<GraphPass> out;
    for (auto p = passes.rbegin(); p != passes.rend(); ++p) {
        const bool live = std::any_of(p->writes.begin(), p->writes.end(),
                                      [&](const Access& w) { return needed[int(w.res)]; });
        if (!live) {
            culled.push_back(p->decl->name);
            continue;
        }
        // (a pass's own scratch, which it writes and then reads, stays with the pass)
        std::vector<Access> writes;
        for (const Access& w : p->writes)
            (needed[int(w.res)] || contains(p->reads, w.res) ? writes : p->unread).push_back(w);
        p->writes = writes;
        for (const Access& w : writes)
            if (!contains(p->reads, w.res)) needed[int(w.res)] = false;
        for (const Access& r : p->reads) needed[int(r.res)] = true;
        out.push_back(*p);
    }
    std::reverse(out.begin(), out.end());
    std::reverse(culled.begin(), culled.end());
    passes = std::move(out);
}

// The resolution a pass works at: its first write's (a pass that writes nothing works at the
// one before it).
Resolution resolutionOf(const GraphPass& p, Resolution before) {
    return p.writes.empty() ? before : resourceDecl(p.writes[0].res).resolution;
}

// Chains: the loops over the tiles. A tiled pass joins the chain before it (one of tiled
// passes at its resolution) when it could run in the chain's loop: each tile through the
// chain's passes in turn, so what a pass reads from them it must read at its own pixel, and it
// may write nothing an earlier pass of the chain reads around its pixel or anywhere (that
// pass's later tiles would read the new values). A pass that is not tiled is a chain of its
// own. (Passes of the half frame beside the frame's in one loop over both grids' tiles were
// tried: the denoiser's half-frame post-blur beside the frame's front end, no faster, and 21
// MiB more at a 1080p image's peak.)
void markChains(std::vector<GraphPass>& passes) {
    int chain = 0;
    std::vector<Res> made;     // written by the current chain
    std::vector<Res> reached;  // read by the current chain beyond the reading pixel
    const auto in = [](const std::vector<Res>& list, Res r) {
        return std::find(list.begin(), list.end(), r) != list.end();
    };
    Resolution at = Resolution::Full;
    for (std::size_t i = 0; i < passes.size(); ++i) {
        GraphPass& p = passes[i];
        const Resolution before = at;
        at = resolutionOf(p, at);
        bool joins = i > 0 && p.decl->tiled && passes[i - 1].decl->tiled && at == before;
        for (const Access& r : p.reads)
            if (in(made, r.res) && r.footprint != Footprint::Pixel) joins = false;
        for (const Access& w : p.writes)
            if (in(reached, w.res)) joins = false;
        if (!joins) {
            ++chain;
            made.clear();
            reached.clear();
        }
        p.chain = chain;
        for (const Access& w : p.writes) made.push_back(w.res);
        for (const Access& r : p.reads)
            if (r.footprint != Footprint::Pixel) reached.push_back(r.res);
    }
}

// Transient memory as the planes' range hands it out (core/plane_memory.h): over the passes in
// order, each transient's planes are placed just before the chain of its first pass (best fit
// among the free blocks, the lowest of equals, else at the top of what has been used) and
// freed just after the chain of its last, a freed block merged with its free neighbours: the
// scheduler takes a chain's planes in its set-ups, before the chain's first tile, and gives
// them back in its finishes, after the last (renderer/frame_scheduler.h). Returns the highest
// top: what the transients need at once, planes of any size and format packed by bytes.
std::size_t placeTransients(std::vector<GraphResource>& resources,
                            const std::vector<GraphPass>& passes) {
    const std::size_t passCount = passes.size();
    // Each pass's chain's first and last pass.
    std::vector<int> chainFirst(passCount), chainLast(passCount);
    for (std::size_t p = 0; p < passCount; ++p)
        chainFirst[p] =
            p > 0 && passes[p].chain == passes[p - 1].chain ? chainFirst[p - 1] : int(p);
    for (std::size_t p = passCount; p-- > 0;)
        chainLast[p] =
            p + 1 < passCount && passes[p].chain == passes[p + 1].chain ? chainLast[p + 1] : int(p);
    std::map<std::size_t, std::size_t> free;  // offset -> bytes, in address order
    std::size_t top = 0, highest = 0;
    const auto place = [&](std::size_t bytes) {
        auto best = free.end();
        for (auto it = free.begin(); it != free.end(); ++it)
            if (it->second >= bytes && (best == free.end() || it->second < best->second)) best = it;
        if (best == free.end()) {
            // At the top, from the last free block where it reaches the top.
            std::size_t at = top;
            if (!free.empty() &&
                std::prev(free.end())->first + std::prev(free.end())->second == top) {
                at = std::prev(free.end())->first;
                free.erase(std::prev(free.end()));
            }
            top = at + bytes;
            highest = std::max(highest, top);
            return at;
        }
        const std::size_t at = best->first, left = best->second - bytes;
        free.erase(best);
        if (left) free[at + bytes] = left;
        return at;
    };
    const auto release = [&](std::size_t at, std::size_t bytes) {
        auto next = free.lower_bound(at);
        if (next != free.begin() && std::prev(next)->first + std::prev(next)->second == at) {
            at = std::prev(next)->first;
            bytes += std::prev(next)->second;
            free.erase(std::prev(next));
        }
        if (next != free.end() && at + bytes == next->first) {
            bytes += next->second;
            free.erase(next);
        }
        free[at] = bytes;
    };
    for (std::size_t p = 0; p < passCount; ++p) {
        for (GraphResource& r : resources) {
            if (r.lifetime != Lifetime::Transient || chainFirst[std::size_t(r.first)] != int(p))
                continue;
            const int planes = planesOf(resourceDecl(r.id));
            for (int i = 0; i < planes; ++i)
                r.offsets.push_back(place(r.bytes / std::size_t(planes)));
        }
        for (GraphResource& r : resources) {
            if (r.lifetime != Lifetime::Transient || chainLast[std::size_t(r.last)] != int(p))
                continue;
            const std::size_t planeBytes = r.bytes / r.offsets.size();
            for (std::size_t at : r.offsets) release(at, planeBytes);
        }
    }
    return highest;
}

}  // namespace

bool CompiledGraph::runs(std::string_view name) const {
    return std::any_of(passes.begin(), passes.end(),
                       [&](const GraphPass& p) { return p.decl->name == name; });
}

const GraphResource* CompiledGraph::find(Res id) const {
    for (const GraphResource& r : resources)
        if (r.id == id) return &r;
    return nullptr;
}

std::vector<std::string> CompiledGraph::layerNames() const {
    std::vector<std::string> out;
    for (const GraphResource& r : resources)
        if (r.lifetime == Lifetime::Output)
            for (std::string& n : resourceDecl(r.id).channelNames()) out.push_back(std::move(n));
    return out;
}

CompiledGraph compileFrameGraph(const GraphKey& key) {
    key.settings.validate();
    CompiledGraph g;
    const int w = key.settings.width, h = key.settings.height;
    g.width = w;
    g.height = h;
    for (const PassDecl& d : passDecls())
        if (holds(d.enabled, key))
            g.passes.push_back({&d, kept(d.reads, key), kept(d.writes, key)});
    cull(key, g.passes, g.culled);
    markChains(g.passes);
    // Each resource's first and last pass; every read of this frame's resource follows a write.
    std::array<GraphResource, kResourceCount> all{};
    for (int r = 0; r < kResourceCount; ++r) all[r].id = Res(r);
    for (int i = 0; i < int(g.passes.size()); ++i) {
        GraphPass& p = g.passes[i];
        for (const Access& a : p.reads) {
            GraphResource& r = all[int(a.res)];
            const ResourceDecl& d = resourceDecl(a.res);
            // (history is the last frame's; a pass's own scratch is written before it is read)
            if (r.first < 0 && d.lifetime != Lifetime::History && !contains(p.writes, a.res))
                throw std::logic_error("frame graph: pass '" + std::string(p.decl->name) +
                                       "' reads '" + std::string(d.name) +
                                       "' before any pass writes it");
            if (r.first < 0) r.first = i;
            r.last = i;
        }
        for (const std::vector<Access>* list : {&p.writes, &p.unread})
            for (const Access& a : *list) {
                GraphResource& r = all[int(a.res)];
                if (r.first < 0) r.first = i;
                r.last = std::max(r.last, i);
            }
    }
    const int end = int(g.passes.size()) - 1;
    for (GraphResource& r : all) {
        if (r.first < 0) continue;
        const ResourceDecl& d = resourceDecl(r.id);
        r.lifetime = isRoot(d, key) ? d.lifetime : Lifetime::Transient;
        if (r.lifetime != Lifetime::Transient) r.last = end;
        r.bytes = resourceBytes(d, w, h, key.settings.shadowMapSize);
        g.resources.push_back(r);
    }
    for (GraphPass& p : g.passes) {
        for (const Access& a : p.reads) p.bytesRead += g.find(a.res)->bytes;
        for (const Access& a : p.writes) p.bytesWritten += g.find(a.res)->bytes;
        for (const Access& a : p.unread) p.bytesWritten += g.find(a.res)->bytes;
    }
    g.transientBytes = placeTransients(g.resources, g.passes);
    for (const GraphResource& r : g.resources) {
        if (r.lifetime == Lifetime::Output) g.outputBytes += r.bytes;
        if (r.lifetime == Lifetime::History) g.historyBytes += r.bytes;
    }
    return g;
}

std::string frameGraphDot(const CompiledGraph& g) {
    std::ostringstream o;
    const auto quoted = [](std::string_view s) { return "\"" + std::string(s) + "\""; };
    o << "digraph frame {\n  rankdir=LR;\n  node [fontname=\"Helvetica\", fontsize=10];\n";
    for (std::size_t i = 0; i < g.passes.size(); ++i)
        o << "  p" << i << " [shape=box, style=filled, fillcolor=\"#dde8f5\", label="
          << quoted(std::string(g.passes[i].decl->name) + "\\nchain " +
                    std::to_string(g.passes[i].chain))
          << "];\n";
    for (const GraphResource& r : g.resources) {
        const ResourceDecl& d = resourceDecl(r.id);
        const char* colour = r.lifetime == Lifetime::Output    ? "#e3f2d9"
                             : r.lifetime == Lifetime::History ? "#f8e1c8"
                                                               : "#ffffff";
        o << "  r" << int(r.id) << " [shape=ellipse, style=filled, fillcolor=\"" << colour
          << "\", label="
          << quoted(std::string(d.name) + "\\n" + std::to_string(d.channelCount()) + " x " +
                    std::string(pixelFormatName(d.format)) + ", " +
                    std::string(resolutionName(d.resolution)) + ", " +
                    std::string(lifetimeName(r.lifetime)))
          << "];\n";
    }
    for (std::size_t i = 0; i < g.passes.size(); ++i) {
        for (const Access& a : g.passes[i].reads)
            o << "  r" << int(a.res) << " -> p" << i
              << (a.footprint == Footprint::Pixel    ? ""
                  : a.footprint == Footprint::Around ? " [style=dashed]"
                                                     : " [style=dotted]")
              << ";\n";
        for (const Access& a : g.passes[i].writes)
            o << "  p" << i << " -> r" << int(a.res) << ";\n";
    }
    o << "}\n";
    return o.str();
}

}  // namespace ssrt
