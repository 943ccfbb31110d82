// The back-face depth layer (issue 29): how far behind the visible surface its object goes.
// The depth buffer alone cannot tell a 2 cm pole from a wall, so the marchers used to assume
// every surface a fixed share of its depth thick (MarchSettings::thickness): too thick for
// thin parts (false hits behind them) and too thin for large ones (rays slipping through).
// A second raster of back faces only (RasterView::faces = Faces::Back) gives, per pixel, the
// nearest back face; where that face belongs to the instance the visibility pass sees there
// and lies behind it, the surface is solid from its depth to the back face's: the interval
// the marchers test a ray against. Elsewhere (no back face behind: an open or one-sided
// surface, another object's back face, a cut-out) the interval is unknown and the marchers
// fall back on the relative thickness.
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"
#include "raster/raster.h"

namespace ssrt {

// backZ (ensureSize'd, every pixel written): the back face's positive view depth where it is
// known as above, 0 elsewhere. `front` and `back` are the visibility pass's and the back-face
// pass's buffers (ids and perspective depth keys 1/w) of the same size; `triangleOffset` is
// TransformedVertices::triangleOffset, which tells each global triangle id's instance. Rows
// are cut across `threads` workers; each pixel depends on its own inputs alone.
void resolveBackDepth(const VisibilityBuffer& front, const VisibilityBuffer& back,
                      const std::vector<uint32_t>& triangleOffset, PlaneF& backZ, int threads);

}  // namespace ssrt
