#include "shading/composite.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "core/plane_view.h"
#include "core/tiles.h"
#include "shading/composite_kernel.h"

namespace ssrt {

namespace {

bool anyOf(const ViewF v[3]) { return v[0] || v[1] || v[2]; }
bool anyOf(const FloatView v[3]) { return v[0] || v[1] || v[2]; }

// A view as requireViews sees it (a part: the view of its format), named by its field where
// its caller left it unnamed (a view never set).
template <class T>
ViewShape shapeOf(const PlaneView<T>& v, std::string_view field) {
    ViewShape s(v);
    if (s.name.empty()) s.name = field;
    return s;
}
ViewShape shapeOf(const FloatView& p, std::string_view field) {
    return p.f16 ? shapeOf(p.f16, field) : shapeOf(p.f32, field);
}
template <class View>
void addRgb(std::vector<ViewShape>& to, const View rgb[3], std::string_view field) {
    for (int c = 0; c < 3; ++c) to.push_back(shapeOf(rgb[c], field));
}

}  // namespace

Compositor::Compositor(Isa isa, const CompositeArgs& args, bool tileSsgi)
    : args_(args), tileSsgi_(tileSsgi) {
    CompositeArgs& a = args_;
    const bool ssgi = tileSsgi || anyOf(a.ssgi), ssr = anyOf(a.ssrColor) || a.ssrOpacity;
    // The views this run reads and writes, direct's first (the size of all of them).
    std::vector<ViewShape> views;
    addRgb(views, a.direct, "direct");
    addRgb(views, a.envSpecular, "envSpecular");
    addRgb(views, a.specWeight, "specWeight");
    if (anyOf(a.emission)) addRgb(views, a.emission, "emission");
    if (!ssgi) addRgb(views, a.envDiffuse, "envDiffuse");
    if (tileSsgi) std::fill_n(a.ssgi, 3, ViewF{});  // each tile's come with it
    else if (ssgi) addRgb(views, a.ssgi, "ssgi");
    if (ssgi && a.occlusion) views.push_back(shapeOf(a.occlusion, "occlusion"));
    if (ssr) {
        addRgb(views, a.ssrColor, "ssrColor");
        views.push_back(shapeOf(a.ssrOpacity, "ssrOpacity"));
    }
    if (anyOf(a.specular)) addRgb(views, a.specular, "specular");
    addRgb(views, a.color, "color");
    addRgb(views, a.display, "display");
    const int w = views.front().width, h = views.front().height;
    a.stride = requireViews("composite", w, h, views.data(), views.size());
    if (ssgi) requireGBuffer("composite", a.g, kGViewZ | kGAlbedo | kGMetallic, w, h);
    grid_ = TileGrid(w, h);
    a.width = w;
    a.height = h;
    a.tilesX = grid_.tilesX;
    a.ssgiX0 = a.ssgiY0 = 0;
    kernel_ = SSRT_DISPATCH(isa, compositeTile);
}

void Compositor::tile(int tile, const ViewF* ssgi, int x0, int y0) const {
    if (!tileSsgi_) {
        if (ssgi) throw std::invalid_argument("composite: SSGI planes given twice");
        return kernel_(args_, tile);
    }
    if (!ssgi) throw std::invalid_argument("composite: the tile's SSGI planes are missing");
    const int w = ssgi[0].width, h = ssgi[0].height;
    requireViews("composite", w, h, {ssgi[0], ssgi[1], ssgi[2]});
    if (!holdsTile({x0, y0}, w, h, grid_.rect(tile)))
        throw std::invalid_argument("composite: the SSGI planes do not hold the tile");
    CompositeArgs a = args_;
    std::copy_n(ssgi, 3, a.ssgi);
    a.ssgiX0 = x0;
    a.ssgiY0 = y0;
    kernel_(a, tile);
}

void composite(Isa isa, const CompositeArgs& args, int threads) {
    const Compositor c(isa, args);
    parallelForTiles(c.grid().count(), threads, [&](int tile) { c.tile(tile); });
}

}  // namespace ssrt
