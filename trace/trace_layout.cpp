#include "trace/trace_layout.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/plane_view.h"
#include "core/tiles.h"

namespace ssrt {

namespace {

constexpr std::string_view kLayoutPass = "buildHalfFrame";

}  // namespace

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
    const GBufferView& g = src.g;
    const bool withGuides = src.guides;
    requireGBuffer(kLayoutPass, g,
                   kGViewZ | kGNormal | kGAlbedo | kGMetallic | (withGuides ? kGMotion : 0),
                   full.width, full.height);
    // Without src.hitLight the half frame's holds its chosen pixels' already (the direct pass
    // wrote them: DirectArgs::hitLightHalf).
    const bool hitLight = src.hitLight[0] || src.hitLight[1] || src.hitLight[2];
    if (hitLight)
        requireViews(kLayoutPass, full.width, full.height,
                     {src.hitLight[0], src.hitLight[1], src.hitLight[2]});
    out.camera = halfCamera(full);
    out.offset = halfOffset(frame);
    const PixelPoint point = halfPixelPoint(out.offset);
    out.camera.pointX = point.x;
    out.camera.pointY = point.y;
    const int hw = out.camera.width, hh = out.camera.height;
    const int w = full.width, h = full.height;
    if (!hitLight)
        out.forEachPlane([&](std::string_view name, const auto& p) {
            for (const PlaneU16& given : out.hitLight)
                if (static_cast<const void*>(&p) == &given)
                    requireViews(kLayoutPass, hw, hh, {viewOf(given, name)});
        });
    // What each half pixel copies from its chosen pixel (`chosen`), and from its block's
    // first pixel for the denoiser's guides (`guides`; motion halved).
    // (Every source is of the frame's size: one stride, g's.)
    struct Copy {
        PlaneF* to;
        const float* from;
        float scale = 1.0f;
    };
    std::vector<Copy> chosen = {{&out.viewZ, g.viewZ}, {&out.metallic, g.metallic}};
    if (src.backZ) {
        requireViews(kLayoutPass, w, h, {src.backZ});
        chosen.push_back({&out.backZ, src.backZ.data});
        if (src.backZ.stride != g.stride)
            throw std::invalid_argument("buildHalfFrame: backZ and viewZ of different strides");
    } else {
        out.backZ = PlaneF();
    }
    if (src.ids) {
        requireViews(kLayoutPass, w, h, {src.ids});
        out.ids.ensureSize(hw, hh);
    } else {
        out.ids = PlaneU32();
    }
    for (int c = 0; c < 3; ++c) {
        chosen.push_back({&out.normal[c], g.normal[c]});
        chosen.push_back({&out.albedo[c], g.albedo[c]});
    }
    if (hitLight)
        for (PlaneU16& p : out.hitLight) p.ensureSize(hw, hh);
    std::vector<Copy> guides = {{&out.guide.viewZ, g.viewZ}};
    for (int c = 0; c < 3; ++c) guides.push_back({&out.guide.normal[c], g.normal[c]});
    // (Motion in half pixels: halving is exact.)
    for (int c = 0; c < 2; ++c) guides.push_back({&out.guide.motion[c], g.motion[c], 0.5f});
    // (Sized one by one: the guides are not made and freed again on every frame without them.)
    for (const Copy& p : chosen) p.to->ensureSize(hw, hh);
    for (const Copy& p : guides) {
        if (withGuides) p.to->ensureSize(hw, hh);
        else *p.to = PlaneF();
    }
    // Rows of half pixels, each row's count of full-resolution surface pixels left out,
    // summed in row order (the same total for every thread count).
    std::vector<uint64_t> rowCut(std::size_t(hh), 0);
    const PixelOffset o = out.offset;
    parallelFor(hh, threads, [&](int hy) {
        // Plane by plane along the row, through row pointers (a plane's members reloaded per
        // pixel cost more than the copy).
        const int sy = halfSource(0, hy, o, w, h).y, gy = halfSource(0, hy, {0, 0}, w, h).y;
        for (const Copy& p : chosen) {
            const float* in = p.from + std::size_t(sy) * g.stride;
            float* to = p.to->row(hy);
            for (int hx = 0; hx < hw; ++hx) to[hx] = in[halfSource(hx, hy, o, w, h).x];
        }
        if (src.ids) {
            const uint32_t* in = src.ids.row(sy);
            uint32_t* to = out.ids.row(hy);
            for (int hx = 0; hx < hw; ++hx) to[hx] = in[halfSource(hx, hy, o, w, h).x];
        }
        if (hitLight)
            for (int c = 0; c < 3; ++c) {  // (f16 bits)
                const uint16_t* in = src.hitLight[c].row(sy);
                uint16_t* to = out.hitLight[c].row(hy);
                for (int hx = 0; hx < hw; ++hx) to[hx] = in[halfSource(hx, hy, o, w, h).x];
            }
        if (withGuides)
            for (const Copy& p : guides) {
                const float* in = p.from + std::size_t(gy) * g.stride;
                float* to = p.to->row(hy);
                for (int hx = 0; hx < hw; ++hx)
                    to[hx] = p.scale * in[halfSource(hx, hy, {0, 0}, w, h).x];
            }
        uint64_t cut = 0;
        for (int y = 2 * hy; y < std::min(2 * hy + 2, h); ++y) {
            const float* z = g.viewZ + std::size_t(y) * g.stride;
            for (int x = 0; x < w; ++x) {
                const PixelOffset s = halfSource(x / 2, hy, o, w, h);
                if (z[x] > 0.0f && !(x == s.x && y == s.y)) ++cut;
            }
        }
        rowCut[std::size_t(hy)] = cut;
    });
    out.cutPixels = 0;
    for (uint64_t c : rowCut) out.cutPixels += c;
}

GBufferView HalfFrame::view() const {
    return gbufferView("the half frame", camera.width, camera.height, *this);
}

}  // namespace ssrt
