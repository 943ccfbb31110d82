#include "shading/composite.h"

#include <stdexcept>
#include <string>

#include "core/tiles.h"
#include "shading/composite_kernel.h"

namespace ssrt {

namespace {

const float* need(const PlaneF* p, int w, int h, const char* what) {
    if (!p || p->width() != w || p->height() != h)
        throw std::invalid_argument(std::string("composite: ") + what +
                                    " missing or not of one size");
    return p->row(0);
}

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
    a.stride = color[0].stride();
    const bool ssgi = anyOf(in.ssgi), ssr = anyOf(in.ssrColor) || in.ssrOpacity;
    for (int c = 0; c < 3; ++c) {
        a.direct[c] = need(in.direct[c], w, h, "direct");
        a.envSpecular[c] = need(in.envSpecular[c], w, h, "envSpecular");
        a.specWeight[c] = need(in.specWeight[c], w, h, "specWeight");
        if (anyOf(in.emission)) a.emission[c] = need(in.emission[c], w, h, "emission");
        if (ssgi) {
            a.ssgi[c] = need(in.ssgi[c], w, h, "ssgi");
            a.albedo[c] = need(in.albedo[c], w, h, "albedo");
        } else {
            a.envDiffuse[c] = need(in.envDiffuse[c], w, h, "envDiffuse");
        }
        if (ssr) a.ssrColor[c] = need(in.ssrColor[c], w, h, "ssrColor");
        if (anyOf(in.specular)) a.specular[c] = need(in.specular[c], w, h, "specular");
        a.color[c] = color[c].row(0);
        a.display[c] = display[c].row(0);
    }
    if (ssgi) {
        a.viewZ = need(in.viewZ, w, h, "viewZ");
        a.metallic = need(in.metallic, w, h, "metallic");
        if (in.occlusion) a.occlusion = need(in.occlusion, w, h, "occlusion");
    }
    if (ssr) a.ssrOpacity = need(in.ssrOpacity, w, h, "ssrOpacity");
    a.exposure = in.exposure;
    const auto tileFn = SSRT_DISPATCH(isa, compositeTile);
    parallelForTiles(grid.count(), threads, [&](int tile) { tileFn(a, tile); });
}

}  // namespace ssrt
