#include "shading/composite.h"

#include <stdexcept>

#include "core/plane_check.h"
#include "core/tiles.h"
#include "shading/composite_kernel.h"

namespace ssrt {

namespace {

bool anyOf(const PlaneF* const p[3]) { return p[0] || p[1] || p[2]; }
bool anyOf(const FloatPlane p[3]) { return p[0] || p[1] || p[2]; }

}  // namespace

Compositor::Compositor(Isa isa, const CompositeInputs& in, PlaneF color[3], PlaneF display[3],
                       bool tileSsgi)
    : tileSsgi_(tileSsgi) {
    if (!in.direct[0]) throw std::invalid_argument("composite: direct missing");
    const int w = in.direct[0].width(), h = in.direct[0].height();
    if (w <= 0 || h <= 0) throw std::invalid_argument("composite: empty planes");
    for (int c = 0; c < 3; ++c) {
        color[c].ensureSize(w, h);
        display[c].ensureSize(w, h);
    }
    grid_ = TileGrid(w, h);
    CompositeArgs& a = args_;
    a.width = w;
    a.height = h;
    a.tilesX = grid_.tilesX;
    PlaneCheck need("composite", w, h);
    const bool ssgi = tileSsgi || anyOf(in.ssgi), ssr = anyOf(in.ssrColor) || in.ssrOpacity;
    for (int c = 0; c < 3; ++c) {
        a.direct[c] = need(in.direct[c], "direct");
        a.envSpecular[c] = need(in.envSpecular[c], "envSpecular");
        a.specWeight[c] = need(in.specWeight[c], "specWeight");
        if (anyOf(in.emission)) a.emission[c] = need(in.emission[c], "emission");
        if (ssgi) {
            if (!tileSsgi) a.ssgi[c] = need(in.ssgi[c], "ssgi");
        } else {
            a.envDiffuse[c] = need(in.envDiffuse[c], "envDiffuse");
        }
        if (ssr) a.ssrColor[c] = need(in.ssrColor[c], "ssrColor");
        if (anyOf(in.specular)) a.specular[c] = need(in.specular[c], "specular");
        a.color[c] = need.output(color[c], "colour");
        a.display[c] = need.output(display[c], "display");
    }
    if (ssgi) {
        requireGBuffer("composite", in.g, kGViewZ | kGAlbedo | kGMetallic, w, h);
        a.g = in.g;
        if (in.occlusion) a.occlusion = need(in.occlusion, "occlusion");
    }
    if (ssr) a.ssrOpacity = need(in.ssrOpacity, "ssrOpacity");
    a.stride = need.stride();
    a.ssgiStride = a.stride;
    a.exposure = in.exposure;
    kernel_ = SSRT_DISPATCH(isa, compositeTile);
}

void Compositor::tile(int tile, const PlaneF* const ssgi[3], int x0, int y0) const {
    if (!tileSsgi_) {
        if (ssgi) throw std::invalid_argument("composite: SSGI planes given twice");
        return kernel_(args_, tile);
    }
    const TileRect r = grid_.rect(tile);
    if (!ssgi || !ssgi[0] || !ssgi[1] || !ssgi[2])
        throw std::invalid_argument("composite: the tile's SSGI planes are missing");
    const int w = ssgi[0]->width(), h = ssgi[0]->height();
    PlaneCheck need("composite", w, h);
    CompositeArgs a = args_;
    for (int c = 0; c < 3; ++c) a.ssgi[c] = need(ssgi[c], "ssgi");
    if (!holdsTile({x0, y0}, w, h, r))
        throw std::invalid_argument("composite: the SSGI planes do not hold the tile");
    a.ssgiStride = need.stride();
    a.ssgiX0 = x0;
    a.ssgiY0 = y0;
    kernel_(a, tile);
}

void composite(Isa isa, const CompositeInputs& in, PlaneF color[3], PlaneF display[3],
               int threads) {
    const Compositor c(isa, in, color, display);
    parallelForTiles(c.grid().count(), threads, [&](int tile) { c.tile(tile); });
}

}  // namespace ssrt
