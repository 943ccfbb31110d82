// SSGI's multi-bounce feedback as the direct pass adds it into the hit light it writes
// (DirectArgs::prevDiffuse): each surface pixel gains its diffuse colour times the occlusion
// times the previous frame's incoming diffuse light at the nearest pixel of its reprojected
// centre; background pixels, and pixels whose centre moved off the frame, keep their light to
// the bit. (A rendered sequence's bits on every ISA and thread count: ssgi_feedback_test.cpp.)
#include <doctest/doctest.h>

#include <algorithm>

#include "core/tiles.h"
#include "plane_compare.h"
#include "renderer/frame.h"
#include "shading/direct_kernel.h"
#include "shading/energy_tables.h"

using namespace ssrt;

namespace {

constexpr int kW = 90, kH = 50;

// A uniform lit surface (normal +y, towards the light; albedo 0.5, 0.6, 0.7; metallic 0.2),
// the previous frame's light a ramp over the pixels (so that which pixel is read shows),
// motion and occlusion planes to set, and the hit light written as f32 (no rounding).
struct FeedbackFrame {
    GBuffer g;
    PlaneF occlusion{kW, kH, 0.5f};
    PlaneF prev[3] = {PlaneF(kW, kH), PlaneF(kW, kH), PlaneF(kW, kH)};
    PlaneF shadowMap{16, 16, 0.0f};
    PlaneF out[7];  // colour, display, shadow
    DirectArgs args{};

    FeedbackFrame() {
        g.viewZ = PlaneF(kW, kH, 5.0f);
        const float normal[3] = {0.0f, 1.0f, 0.0f}, albedo[3] = {0.5f, 0.6f, 0.7f};
        for (int c = 0; c < 3; ++c) {
            g.normal[c] = PlaneF(kW, kH, normal[c]);
            g.albedo[c] = PlaneF(kW, kH, albedo[c]);
        }
        g.metallic = PlaneF(kW, kH, 0.2f);
        g.roughness = PlaneF(kW, kH, 0.5f);
        g.materialId = PlaneF(kW, kH, 0.0f);
        for (PlaneF& m : g.motion) m = PlaneF(kW, kH, 0.0f);
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                for (int c = 0; c < 3; ++c) prev[c].at(x, y) = prevAt(x, y, c);
        args.width = kW;
        args.height = kH;
        args.tilesX = TileGrid(kW, kH).tilesX;
        args.tanHalfX = 0.6f * float(kW) / float(kH);
        args.tanHalfY = 0.6f;
        const float rot[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, l[3] = {0.0f, 1.0f, 0.0f},
                    e[3] = {2.0f, 3.0f, 4.0f}, sky[3] = {0.3f, 0.4f, 0.5f};
        std::copy_n(rot, 9, args.viewToWorld);
        std::copy_n(l, 3, args.toLight);
        std::copy_n(e, 3, args.lightRadiance);
        std::copy_n(sky, 3, args.skyZenith);
        std::copy_n(sky, 3, args.skyHorizon);
        std::copy_n(sky, 3, args.skyGround);
        args.shadowMap = shadowMap.row(0);
        args.shadowStride = shadowMap.stride();
        args.shadowSize = 16;
        args.exposure = 1.0f;
        args.energy = &energyTables();
        for (PlaneF& p : out) p = PlaneF(kW, kH);
        for (int c = 0; c < 3; ++c) args.color[c] = out[c].row(0);
        args.shadow = out[6].row(0);
        args.outStride = out[0].stride();
    }
    static float prevAt(int x, int y, int c) { return 0.01f * float(x + 1) + 0.1f * float(c + y); }

    // The hit light the kernel writes, with the feedback or without.
    void shade(bool fed, PlaneF hitLight[3]) {
        args.g = g.view();
        for (int c = 0; c < 3; ++c) {
            hitLight[c] = PlaneF(kW, kH);
            args.hitLight[c] = hitLight[c].row(0);
            args.prevDiffuse[c] = fed ? prev[c].row(0) : nullptr;
        }
        const auto fn = SSRT_DISPATCH(defaultIsa(), shadeTile);
        parallelForTiles(TileGrid(kW, kH).count(), 2, [&](int t) { fn(args, t); });
    }
};

}  // namespace

TEST_CASE("direct feedback: each pixel's diffuse colour times last frame's light there") {
    FeedbackFrame f;
    const float albedo[3] = {0.5f, 0.6f, 0.7f};
    PlaneF lit[3], fed[3];
    // How many surface pixels' gain differs from albedo (1 - metallic) occlusion E'(x + dx, y).
    const auto wrong = [&](int dx, float occlusion) {
        int off = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x)
                for (int c = 0; c < 3 && f.g.viewZ.at(x, y) > 0.0f; ++c) {
                    const double prev = x + dx < kW ? FeedbackFrame::prevAt(x + dx, y, c) : 0.0;
                    const double gain = double(fed[c].at(x, y)) - double(lit[c].at(x, y));
                    off += !(gain == doctest::Approx(albedo[c] * 0.8 * occlusion * prev)
                                         .epsilon(1e-5)
                                         .scale(1.0));
                }
        return off;
    };
    // A still camera (motion 0) reads the pixel itself.
    f.shade(false, lit);
    f.shade(true, fed);
    CHECK(lit[1].at(10, 10) > 0.0f);  // the sun lights it: a light to add to
    CHECK(wrong(0, 1.0f) == 0);
    // Moved one pixel right since the last frame (motion = previous - current = +1): the pixel
    // to the right, nothing past the frame's edge; the occlusion scales the bounce; background
    // pixels are left alone, to the bit.
    f.g.motion[0].fill(1.0f);
    f.args.occlusion = f.occlusion.row(0);
    f.g.viewZ.at(3, 4) = 0.0f;
    f.shade(false, lit);
    f.shade(true, fed);
    for (int c = 0; c < 3; ++c) {
        CHECK(fed[c].at(3, 4) == lit[c].at(3, 4));
        CHECK(fed[c].at(kW - 1, 7) == lit[c].at(kW - 1, 7));
    }
    CHECK(wrong(1, 0.5f) == 0);
    // All off the frame: the hit light as it was, to the bit.
    f.g.motion[1].fill(-float(kH));
    f.shade(true, fed);
    for (int c = 0; c < 3; ++c) CHECK(test::sameBits(fed[c], lit[c]));
}
