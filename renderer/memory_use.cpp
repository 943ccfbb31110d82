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
template <class Planes>  // (anything with forEachPlane: a group, the Frame)
PlaneCount planesOf(const Planes& g) {
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
    const PlaneCount count =
        planesOf(f) + planesOf(h) + planesOf(h.denoise) + planesOf(h.denoiseHalf);
    FrameMemoryNeed need;
    need.planes = count.planes;
    need.pixelBytes = count.pixelBytes;
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    need.bytes = count.pixelBytes * pixels +
                 std::size_t(shadowMapSize) * std::size_t(shadowMapSize) * sizeof(float);
    return need;
}

std::vector<MemoryUse> memoryUse(const Frame& f, const FrameHistory* history) {
    // Bytes by resource (table order), then by the group of what no resource declares.
    std::vector<std::size_t> declared(kResourceCount, 0);
    std::vector<MemoryUse> undeclared;
    const auto count = [&](std::string_view group, std::string_view name, const auto& buffer) {
        const std::size_t bytes = bytesOf(buffer);
        if (bytes == 0) return;
        const Res id = resourceOfChannel(name);
        if (id != Res::Count) return void(declared[std::size_t(id)] += bytes);
        for (MemoryUse& m : undeclared)
            if (m.name == group) return void(m.bytes += bytes);
        undeclared.push_back({std::string(group), bytes});
    };
    f.forEachPlane([&](std::string_view name, const auto& p) { count("frame", name, p); });
    f.scratch.forEachBuffer(count);
    if (history) {
        history->forEachPlane(
            [&](std::string_view name, const auto& p) { count("history", name, p); });
        history->denoise.forEachPlane(
            [&](std::string_view name, const auto& p) { count("denoise history", name, p); });
        // (named as the full frame's: counted apart)
        history->denoiseHalf.forEachPlane(
            [&](std::string_view, const auto& p) { count("half denoise history", "", p); });
    }
    std::vector<MemoryUse> out;
    for (int r = 0; r < kResourceCount; ++r)
        if (declared[std::size_t(r)] > 0)
            out.push_back({std::string(resourceDecl(Res(r)).name), declared[std::size_t(r)]});
    out.insert(out.end(), undeclared.begin(), undeclared.end());
    const auto add = [&](const char* name, std::size_t bytes) {
        if (bytes > 0) out.push_back({name, bytes});
    };
    // The planes' range keeps the pages of planes freed (given back after their last pass)
    // for the next: memory this process holds that no plane uses now (the process's, not the
    // frame's alone: another renderer's planes share the range).
    const PlaneMemoryUse range = planeMemoryUse();
    add("free plane memory", range.bytesTouched - range.bytesInUse);
    return out;
}

}  // namespace ssrt
