// The denoiser tests' guides: a wall facing the camera at depth 2 (view = world), both
// signals everywhere, and the ReblurFrame the kernels read them through.
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"
#include "core/tiles.h"
#include "denoise/reblur_kernel.h"

namespace ssrt::test {

struct WallGuides {
    int width, height;
    PlaneF viewZ, normal[3], roughness;
    PlaneF signalZ[2];
    std::vector<uint8_t> tiles;

    WallGuides(int w, int h) : width(w), height(h), viewZ(w, h, 2.0f), roughness(w, h, 0.3f) {
        for (PlaneF& n : normal) n = PlaneF(w, h, 0.0f);
        normal[2].fill(1.0f);
        for (PlaneF& z : signalZ) z = PlaneF(w, h, 2.0f);
        tiles.assign(std::size_t(TileGrid(w, h).count()), kTileDiffuse | kTileSpecular);
    }
    ReblurFrame view() const {
        ReblurFrame v;
        v.width = width;
        v.height = height;
        v.tilesX = TileGrid(width, height).tilesX;
        v.stride = viewZ.stride();
        v.tanHalfY = 0.5f;
        v.tanHalfX = 0.5f * float(width) / float(height);
        for (int i = 0; i < 9; i += 4) v.viewToWorld[i] = 1.0f;
        v.frustum = 1.0f;  // 2 tanHalfY: the short side at depth 1
        v.viewZ = viewZ.row(0);
        for (int i = 0; i < 3; ++i) v.normal[i] = normal[i].row(0);
        v.roughness = roughness.row(0);
        for (int i = 0; i < 2; ++i) v.signalZ[i] = signalZ[i].row(0);
        v.tiles = tiles.data();
        v.hitScale = {2.5f, 0.1f, 20.0f, -25.0f};
        return v;
    }
};

}  // namespace ssrt::test
