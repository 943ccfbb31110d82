#include "shading/composite.h"

#include <stdexcept>

#include "core/plane_check.h"
#include "core/tiles.h"
#include "shading/composite_kernel.h"

namespace ssrt {

namespace {

bool anyOf(const PlaneF* const p[3]) { return p[0] || p[1] || p[2]; }

}  // namespace

void composite(Isa isa, const CompositeInputs& in, PlaneF color[3], PlaneF display[3],
               int threads) {
    if (!in.direct[0]) throw std::invalid_argument("composite: direct missing");
    const int w = in.direct[0]->width(), h = in.direct[0]->height();
    if (w <= 0 || h <= 0) throw std::invalid_argument("composite: empty planes");
    for (int c = 0; c < 3; ++c) {
        color[c].ensureSize(w, h);
        display[c].ensureSize(w, h);
    }
    const TileGrid grid(w, h);
    CompositeArgs a{};
    a.width = w;
    a.height = h;
    a.tilesX = grid.tilesX;
    PlaneCheck need("composite", w, h);
    const bool ssgi = anyOf(in.ssgi), ssr = anyOf(in.ssrColor) || in.ssrOpacity;
    for (int c = 0; c < 3; ++c) {
        a.direct[c] = need(in.direct[c], "direct");
        a.envSpecular[c] = need(in.envSpecular[c], "envSpecular");
        a.specWeight[c] = need(in.specWeight[c], "specWeight");
        if (anyOf(in.emission)) a.emission[c] = need(in.emission[c], "emission");
        if (ssgi) {
            a.ssgi[c] = need(in.ssgi[c], "ssgi");
            a.albedo[c] = need(in.albedo[c], "albedo");
        } else {
            a.envDiffuse[c] = need(in.envDiffuse[c], "envDiffuse");
        }
        if (ssr) a.ssrColor[c] = need(in.ssrColor[c], "ssrColor");
        if (anyOf(in.specular)) a.specular[c] = need(in.specular[c], "specular");
        a.color[c] = need.output(color[c], "colour");
        a.display[c] = need.output(display[c], "display");
    }
    if (ssgi) {
        a.viewZ = need(in.viewZ, "viewZ");
        a.metallic = need(in.metallic, "metallic");
        if (in.occlusion) a.occlusion = need(in.occlusion, "occlusion");
    }
    if (ssr) a.ssrOpacity = need(in.ssrOpacity, "ssrOpacity");
    a.stride = need.stride();
    a.exposure = in.exposure;
    const auto tileFn = SSRT_DISPATCH(isa, compositeTile);
    parallelForTiles(grid.count(), threads, [&](int tile) { tileFn(a, tile); });
}

}  // namespace ssrt
