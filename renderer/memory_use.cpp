#include "renderer/memory_use.h"

#include "core/plane_memory.h"

namespace ssrt {

namespace {

template <class T>
std::size_t bytesOf(const Plane<T>& p) {
    return p.bytes();
}
template <class Group>
std::size_t bytesOf(const PlaneTable<Group>& g) {
    return g.bytes();
}
template <class T, std::size_t N>
std::size_t bytesOf(const T (&array)[N]) {
    std::size_t n = 0;
    for (const T& p : array) n += bytesOf(p);
    return n;
}
std::size_t bytesOf(const HiZPyramid& hiz) {
    std::size_t n = hiz.invMinPacked.size() * sizeof(float);
    for (const PlaneF& p : hiz.minZ) n += p.bytes();
    return n;
}
std::size_t bytesOf(const ColorPyramid& pyramid) {
    std::size_t n = 0;
    for (const auto& level : pyramid.levels)
        n += bytesOf(level[0]) + bytesOf(level[1]) + bytesOf(level[2]);
    return n;
}

// A group's planes and the bytes a pixel takes in them (each plane's own element size).
struct PlaneCount {
    int planes = 0;
    std::size_t pixelBytes = 0;
    PlaneCount operator+(const PlaneCount& o) const {
        return {planes + o.planes, pixelBytes + o.pixelBytes};
    }
};
template <class Group>
PlaneCount planesOf(const PlaneTable<Group>& g) {
    PlaneCount n;
    g.forEachPlane([&](std::string_view, const auto& p) {
        ++n.planes;
        n.pixelBytes += sizeof(*p.row(0));
    });
    return n;
}

}  // namespace

FrameMemoryNeed frameMemoryNeed(int width, int height, int shadowMapSize) {
    const Frame f;
    const FrameHistory h;
    const PlaneCount count = planesOf(f.image) + planesOf(f.gbuffer) + planesOf(f.material) +
                             planesOf(f.ids) + planesOf(f.direct) + planesOf(f.trace.ssr) +
                             planesOf(f.trace.ssgi) + planesOf(f.trace.denoise) + planesOf(h) +
                             planesOf(h.denoise) + planesOf(h.denoiseHalf);
    FrameMemoryNeed need;
    need.planes = count.planes;
    need.pixelBytes = count.pixelBytes;
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    need.bytes = count.pixelBytes * pixels +
                 std::size_t(shadowMapSize) * std::size_t(shadowMapSize) * sizeof(float);
    return need;
}

std::vector<MemoryUse> memoryUse(const Frame& f, const FrameHistory* history) {
    std::vector<MemoryUse> out;
    const auto add = [&](const char* name, std::size_t bytes) {
        if (bytes > 0) out.push_back({name, bytes});
    };
    add("image", bytesOf(f.image));
    add("gbuffer", bytesOf(f.gbuffer));
    add("material", bytesOf(f.material));
    add("ids", bytesOf(f.ids));
    add("direct parts", bytesOf(f.direct));
    add("ssr", bytesOf(f.trace.ssr));
    add("ssgi", bytesOf(f.trace.ssgi));
    add("denoised", bytesOf(f.trace.denoise));
    const Frame::Scratch& s = f.scratch;
    add("visibility buffer", bytesOf(s.visibility.depth) + bytesOf(s.visibility.ids));
    add("back faces",
        bytesOf(s.backVisibility.depth) + bytesOf(s.backVisibility.ids) + bytesOf(s.backZ));
    add("shadow map", bytesOf(s.shadow.depth));
    add("uv", bytesOf(s.uv));
    add("tangent", bytesOf(s.tangent));
    add("hi-z", bytesOf(s.hiz));
    add("rays", bytesOf(s.rays));
    add("march", bytesOf(s.march));
    add("colour pyramid", bytesOf(s.colorPyramid));
    add("ssr resolve", bytesOf(s.ssr));
    add("denoise scratch", bytesOf(s.denoise));
    add("half frame", bytesOf(s.half.frame));
    add("half hi-z", bytesOf(s.half.hiz));
    add("half rays", bytesOf(s.half.rays));
    add("half march", bytesOf(s.half.march));
    add("half resolved", bytesOf(s.half.resolved));
    add("half denoise scratch", bytesOf(s.half.denoise));
    add("half denoised", bytesOf(s.half.denoised));
    if (history) {
        add("history", bytesOf(*history));
        add("denoise history", bytesOf(history->denoise));
        add("half denoise history", bytesOf(history->denoiseHalf));
    }
    // The planes' range keeps the pages of planes freed (given back after their last pass)
    // for the next: memory this process holds that no plane uses now (the process's, not the
    // frame's alone: another renderer's planes share the range).
    const PlaneMemoryUse range = planeMemoryUse();
    add("free plane memory", range.bytesTouched - range.bytesInUse);
    return out;
}

}  // namespace ssrt
