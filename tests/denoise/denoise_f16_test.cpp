// The denoiser keeps its signals in f16 (denoise/denoise.h) and computes in f32: each pass
// decodes what it reads and encodes what it writes with the library's conversions
// (core/pixel_formats.h). So a pass over f16 planes must give, bit for bit, the f16 encoding of
// what it gives over f32 planes that hold the same (f16-exact) values: on every ISA this
// machine runs, through plain loads and through gathers (a temporal read through a motion that
// differs per pixel).
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "core/image.h"
#include "core/isa.h"
#include "core/pixel_formats.h"
#include "core/rng.h"
#include "core/tiles.h"
#include "denoise/reblur_kernel.h"
#include "denoise/reblur_wall.h"

using namespace ssrt;

namespace {

constexpr int kWidth = 2 * kTileSize + 16, kHeight = 40;

std::vector<Isa> runnableIsas() {
    std::vector<Isa> isas;
    for (Isa isa : kAllIsas)
        if (isaSupported(isa)) isas.push_back(isa);
    return isas;
}

template <class Fn>
void forEachTile(Fn&& fn) {
    const TileGrid grid(kWidth, kHeight);
    for (int t = 0; t < grid.count(); ++t) fn(t);
}

// Four channels both ways: f32 planes holding f16-exact values, and their f16 bits.
struct Signal {
    PlaneF f[4];
    PlaneU16 h[4];
    // Noisy radiance in [0, 8) (channel 3, the hit distance, in [0, 1)), some pixels much
    // brighter, a few zero.
    explicit Signal(uint32_t seed) {
        for (int c = 0; c < 4; ++c) {
            f[c] = PlaneF(kWidth, kHeight, 0.0f);
            h[c] = PlaneU16(kWidth, kHeight, 0);
            for (int y = 0; y < kHeight; ++y)
                for (int x = 0; x < kWidth; ++x) {
                    float v = randomFloat(uint32_t(y * kWidth + x), seed, 11, uint32_t(c));
                    if (c < 3) v *= (x * 7 + y * 3) % 29 == 0 ? 3000.0f : 8.0f;
                    if ((x + y) % 31 == 0) v = 0.0f;
                    h[c].at(x, y) = encodeF16(v);
                    f[c].at(x, y) = decodeF16(h[c].at(x, y));
                }
        }
    }
    // Outputs: f32 and f16 planes of another fill.
    Signal() {
        for (int c = 0; c < 4; ++c)
            f[c] = PlaneF(kWidth, kHeight, -1.0f), h[c] = PlaneU16(kWidth, kHeight, 0);
    }
};

// Every visible pixel of `half` is encodeF16 of `full`'s.
bool encodes(const PlaneF& full, const PlaneU16& half) {
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            if (half.at(x, y) != encodeF16(full.at(x, y))) return false;
    return true;
}

bool sameBits(const PlaneF& a, const PlaneF& b) {
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            if (std::signbit(a.at(x, y)) != std::signbit(b.at(x, y)) ||
                !(a.at(x, y) == b.at(x, y) || (std::isnan(a.at(x, y)) && std::isnan(b.at(x, y)))))
                return false;
    return true;
}

struct Wall : test::WallGuides {
    Wall() : WallGuides(kWidth, kHeight) {
        // Some relief, so that the edge stops weigh taps differently.
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x)
                viewZ.at(x, y) = signalZ[0].at(x, y) = signalZ[1].at(x, y) =
                    2.0f + 0.01f * float((x * 13 + y * 7) % 17);
    }
};

}  // namespace

TEST_CASE("denoise f16 storage: the temporal pass over f16 planes is its f32 result encoded") {
    for (const Isa isa : runnableIsas()) {
        CAPTURE(isaName(isa));
        for (const bool specular : {false, true}) {
            CAPTURE(specular);
            Wall g;
            const Signal in(1), previous(2);
            const Signal fast(3);  // (channel 0 serves as the fast history's luma)
            Signal out, outFast;
            PlaneF motion[2] = {PlaneF(kWidth, kHeight), PlaneF(kWidth, kHeight)};
            for (int y = 0; y < kHeight; ++y)
                for (int x = 0; x < kWidth; ++x) {
                    // Per pixel, fractional: the history taps are gathers, not runs.
                    motion[0].at(x, y) = 0.37f * float((x * 5 + y) % 7) - 1.1f;
                    motion[1].at(x, y) = 0.21f * float((x + 3 * y) % 5) - 0.4f;
                }
            PlaneF prevFrames(kWidth, kHeight, 4.0f), outFrames[2];
            for (PlaneF& p : outFrames) p = PlaneF(kWidth, kHeight, -1.0f);
            ReblurPassArgs a;
            a.frame = g.view();
            a.specular = specular;
            a.frame.motion[0] = motion[0].row(0), a.frame.motion[1] = motion[1].row(0);
            a.frame.prev.viewZ = g.viewZ.row(0);
            for (int i = 0; i < 3; ++i) a.frame.prev.normal[i] = g.normal[i].row(0);
            a.frame.prev.roughness = g.roughness.row(0);
            a.prevFrames = prevFrames.row(0);
            for (int i = 0; i < 9; i += 4) a.frame.prevViewToWorld[i] = 1.0f;
            a.frame.prevTanHalfX = a.frame.tanHalfX;
            a.frame.prevTanHalfY = a.frame.tanHalfY;
            a.frame.cameraDelta[0] = 0.01f;
            const auto fn = SSRT_DISPATCH(isa, reblurTemporalTile);
            // f32 planes
            for (int c = 0; c < 4; ++c) {
                a.in[c] = in.f[c].row(0), a.out[c] = out.f[c].row(0);
                a.prevSignal[c] = previous.f[c].row(0);
            }
            a.prevFast = fast.f[0].row(0);
            a.outFast = outFast.f[0].row(0);
            a.outFrames = outFrames[0].row(0);
            forEachTile([&](int t) { fn(a, t); });
            // f16 planes
            for (int c = 0; c < 4; ++c) {
                a.in[c] = in.h[c].row(0), a.out[c] = out.h[c].row(0);
                a.prevSignal[c] = previous.h[c].row(0);
            }
            a.prevFast = fast.h[0].row(0);
            a.outFast = outFast.h[0].row(0);
            a.outFrames = outFrames[1].row(0);
            forEachTile([&](int t) { fn(a, t); });
            for (int c = 0; c < 4; ++c) {
                CAPTURE(c);
                CHECK(encodes(out.f[c], out.h[c]));
            }
            CHECK(encodes(outFast.f[0], outFast.h[0]));
            CHECK(sameBits(outFrames[0], outFrames[1]));
            // The history was read: not every pixel starts afresh.
            CHECK(outFrames[0].at(kWidth / 2, kHeight / 2) > 0.0f);
        }
    }
}

TEST_CASE(
    "denoise f16 storage: the spatial passes and the history fix over f16 planes are "
    "their f32 results encoded") {
    for (const Isa isa : runnableIsas()) {
        CAPTURE(isaName(isa));
        for (const bool specular : {false, true}) {
            CAPTURE(specular);
            Wall g;
            g.tiles[1] = 0;  // a tile without the signal: copied between the formats
            const Signal in(4), fast(5);
            PlaneF frames(kWidth, kHeight);
            for (int y = 0; y < kHeight; ++y)
                for (int x = 0; x < kWidth; ++x) frames.at(x, y) = float((x + y) % 9);
            for (const ReblurSpatial pass :
                 {ReblurSpatial::PreBlur, ReblurSpatial::Blur, ReblurSpatial::PostBlur}) {
                CAPTURE(int(pass));
                Signal out, copy;
                ReblurPassArgs a;
                a.frame = g.view();
                a.pass = pass;
                a.specular = specular;
                a.frames = pass == ReblurSpatial::PreBlur ? nullptr : frames.row(0);
                a.frame.frameIndex = 7;
                a.radius = 12.0f;
                const auto fn = SSRT_DISPATCH(isa, reblurSpatialTile);
                for (int c = 0; c < 4; ++c)
                    a.in[c] = in.f[c].row(0), a.out[c] = out.f[c].row(0),
                    a.copy[c] = copy.f[c].row(0);
                forEachTile([&](int t) { fn(a, t); });
                // The post-blur as the denoiser runs it: RGB to f32 outputs, all four to the
                // f16 history; the others f16 to f16.
                PlaneF rgb[3];
                for (int c = 0; c < 4; ++c) {
                    a.in[c] = in.h[c].row(0);
                    a.copy[c] =
                        pass == ReblurSpatial::PostBlur ? SignalOut(copy.h[c].row(0)) : SignalOut();
                    if (pass != ReblurSpatial::PostBlur) a.out[c] = out.h[c].row(0);
                    else if (c < 3) a.out[c] = (rgb[c] = PlaneF(kWidth, kHeight, -2.0f)).row(0);
                    else a.out[c] = nullptr;
                }
                forEachTile([&](int t) { fn(a, t); });
                for (int c = 0; c < 4; ++c) {
                    CAPTURE(c);
                    if (pass != ReblurSpatial::PostBlur) {
                        CHECK(encodes(out.f[c], out.h[c]));
                        continue;
                    }
                    CHECK(encodes(copy.f[c], copy.h[c]));
                    if (c < 3) CHECK(sameBits(rgb[c], out.f[c]));
                }
            }
            Signal out;
            ReblurPassArgs a;
            a.frame = g.view();
            a.specular = specular;
            a.frames = frames.row(0);
            a.frame.historyFixStride = 6.0f;
            const auto fn = SSRT_DISPATCH(isa, reblurHistoryFixTile);
            for (int c = 0; c < 4; ++c) a.in[c] = in.f[c].row(0), a.out[c] = out.f[c].row(0);
            a.fast = fast.f[0].row(0);
            forEachTile([&](int t) { fn(a, t); });
            for (int c = 0; c < 4; ++c) a.in[c] = in.h[c].row(0), a.out[c] = out.h[c].row(0);
            a.fast = fast.h[0].row(0);
            forEachTile([&](int t) { fn(a, t); });
            for (int c = 0; c < 4; ++c) {
                CAPTURE(c);
                CHECK(encodes(out.f[c], out.h[c]));
            }
        }
    }
}
