#include "trace/trace_layout.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/plane_check.h"
#include "core/tiles.h"

namespace ssrt {

std::string_view traceLayoutName(TraceLayout layout) {
    switch (layout) {
        case TraceLayout::Full: return "full";
        case TraceLayout::Checkerboard: return "checkerboard";
        case TraceLayout::Half: return "half";
    }
    return "?";
}

std::optional<TraceLayout> parseTraceLayout(std::string_view name) {
    for (TraceLayout l : {TraceLayout::Full, TraceLayout::Checkerboard, TraceLayout::Half})
        if (traceLayoutName(l) == name) return l;
    return std::nullopt;
}

TraceCamera halfCamera(const TraceCamera& full) {
    TraceCamera c = full;
    c.width = (full.width + 1) / 2;
    c.height = (full.height + 1) / 2;
    c.tanHalfX = full.tanHalfX * (float(2 * c.width) / float(full.width));
    c.tanHalfY = full.tanHalfY * (float(2 * c.height) / float(full.height));
    return c;
}

void buildHalfFrame(const TraceCamera& full, const HalfFrameSource& src, uint32_t frame,
                    HalfFrame& out, int threads) {
    if (full.width <= 0 || full.height <= 0)
        throw std::invalid_argument("buildHalfFrame: the camera has no pixels");
    PlaneCheck need("buildHalfFrame", full.width, full.height);
    need(src.viewZ, "viewZ");
    need(src.metallic, "metallic");
    // Without src.hitLight the half frame's holds its chosen pixels' already (the direct pass
    // wrote them: DirectArgs::hitLightHalf).
    const bool hitLight = src.hitLight[0] || src.hitLight[1] || src.hitLight[2];
    for (int c = 0; c < 3; ++c) {
        need(src.normal[c], "normal");
        need(src.albedo[c], "albedo");
        if (hitLight) need(src.hitLight[c], "hitLight");
    }
    out.camera = halfCamera(full);
    out.offset = halfOffset(frame);
    const int hw = out.camera.width, hh = out.camera.height;
    const int w = full.width, h = full.height;
    if (!hitLight) {
        PlaneCheck given("buildHalfFrame", hw, hh);
        for (PlaneF& p : out.hitLight) given(p, "the half frame's hitLight");
    }
    PlaneF* dst[11] = {&out.viewZ,       &out.normal[0],   &out.normal[1],  &out.normal[2],
                       &out.albedo[0],   &out.albedo[1],   &out.albedo[2],  &out.metallic,
                       &out.hitLight[0], &out.hitLight[1], &out.hitLight[2]};
    const PlaneF* from[11] = {src.viewZ,       src.normal[0],   src.normal[1],  src.normal[2],
                              src.albedo[0],   src.albedo[1],   src.albedo[2],  src.metallic,
                              src.hitLight[0], src.hitLight[1], src.hitLight[2]};
    const int copied = hitLight ? 11 : 8;
    const bool guides = src.motion[0] != nullptr;
    if (guides)
        for (int c = 0; c < 2; ++c) need(src.motion[c], "motion");
    PlaneF* const guide[6] = {&out.guideZ,         &out.guideNormal[0], &out.guideNormal[1],
                              &out.guideNormal[2], &out.guideMotion[0], &out.guideMotion[1]};
    const PlaneF* const guideFrom[6] = {src.viewZ,     src.normal[0], src.normal[1],
                                        src.normal[2], src.motion[0], src.motion[1]};
    // (Sized one by one: the guides are not made and freed again on every frame without them.)
    for (PlaneF* p : dst) p->ensureSize(hw, hh);
    for (PlaneF* p : guide) {
        if (guides) p->ensureSize(hw, hh);
        else *p = PlaneF();
    }
    // Rows of half pixels, each row's count of full-resolution surface pixels left out,
    // summed in row order (the same total for every thread count).
    std::vector<uint64_t> rowCut(std::size_t(hh), 0);
    const PixelOffset o = out.offset;
    parallelFor(hh, threads, [&](int hy) {
        // Plane by plane along the row, through row pointers (a plane's members reloaded per
        // pixel cost more than the copy).
        const int sy = halfSource(0, hy, o, w, h).y, gy = halfSource(0, hy, {0, 0}, w, h).y;
        for (int p = 0; p < copied; ++p) {
            const float* in = from[p]->row(sy);
            float* to = dst[p]->row(hy);
            for (int hx = 0; hx < hw; ++hx) to[hx] = in[halfSource(hx, hy, o, w, h).x];
        }
        if (guides)
            for (int p = 0; p < 6; ++p) {
                const float* in = guideFrom[p]->row(gy);
                float* to = guide[p]->row(hy);
                // (Motion in half pixels: halving is exact.)
                const float scale = p < 4 ? 1.0f : 0.5f;
                for (int hx = 0; hx < hw; ++hx)
                    to[hx] = scale * in[halfSource(hx, hy, {0, 0}, w, h).x];
            }
        uint64_t cut = 0;
        for (int y = 2 * hy; y < std::min(2 * hy + 2, h); ++y)
            for (int x = 0; x < w; ++x) {
                const PixelOffset s = halfSource(x / 2, hy, o, w, h);
                if (src.viewZ->at(x, y) > 0.0f && !(x == s.x && y == s.y)) ++cut;
            }
        rowCut[std::size_t(hy)] = cut;
    });
    out.cutPixels = 0;
    for (uint64_t c : rowCut) out.cutPixels += c;
}

}  // namespace ssrt
