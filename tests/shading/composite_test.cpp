// The composite against the direct pass: with SSR and SSGI off it rebuilds the direct
// kernel's color and display to the bit (every ISA); the optional parts do not change the
// direct kernel's own outputs; SSR at opacity 0 or 1 and SSGI blend as the formula says.
#include "shading/composite.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/pixel_formats.h"
#include "core/rng.h"
#include "core/tiles.h"
#include "plane_compare.h"
#include "renderer/direct_lighting.h"
#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "shading/direct_kernel.h"
#include "shading/multiscatter.h"
#include "thread_counts.h"

using namespace ssrt;

namespace {

using test::sameBits;

// A rendered G-buffer and the direct pass re-run by hand on it, with a noisy shadow map,
// emissive materials and a gradient sky, so that every part is non-trivial.
struct DirectFixture {
    Frame frame;
    std::vector<float> emissive;
    PlaneF shadowMap;
    DirectArgs args{};
    PlaneF out[7];  // color, display, shadow
    PlaneF direct[3], emission[3], envDiffuse[3], envSpecular[3], specWeight[3];

    explicit DirectFixture(const char* scene, float exposure = 1.0f) {
        RenderSettings rs;
        rs.width = 150;  // not a multiple of the tile or of any lane width
        rs.height = 70;
        rs.shadowMapSize = 64;
        rs.threads = 2;
        frame = Renderer(rs).renderWithoutHistory(makeBuiltinScene(scene));
        const int w = frame.width, h = frame.height;
        setDirectGBuffer(frame.gbuffer, args);
        args.width = w;
        args.height = h;
        args.tilesX = TileGrid(w, h).tilesX;
        args.tanHalfX = 0.6f * float(w) / float(h);
        args.tanHalfY = 0.6f;
        const float camPos[3] = {0.1f, 1.0f, 3.0f};
        std::copy_n(camPos, 3, args.camPos);
        const float rot[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        std::copy_n(rot, 9, args.viewToWorld);
        const float l[3] = {0.36f, 0.8f, 0.48f};
        std::copy_n(l, 3, args.toLight);
        const float e[3] = {3.0f, 2.5f, 2.0f};
        std::copy_n(e, 3, args.lightRadiance);
        args.skyGradient = true;
        const float zen[3] = {0.2f, 0.3f, 0.9f}, hor[3] = {0.7f, 0.7f, 0.8f},
                    gnd[3] = {0.2f, 0.15f, 0.1f};
        std::copy_n(zen, 3, args.skyZenith);
        std::copy_n(hor, 3, args.skyHorizon);
        std::copy_n(gnd, 3, args.skyGround);
        const PlaneF& mat = frame.gbuffer.materialId;
        int materials = 1;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) materials = std::max(materials, int(mat.at(x, y)) + 1);
        for (int m = 0; m < materials; ++m)
            for (int c = 0; c < 3; ++c) emissive.push_back(m % 2 ? 0.25f * float(c + 1) : 0.0f);
        args.emissive = emissive.data();
        args.anyEmissive = true;
        shadowMap = PlaneF(16, 16);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
                shadowMap.at(x, y) = randomFloat(uint32_t(y * 16 + x), 3, 0, 0);
        args.shadowMap = shadowMap.row(0);
        args.shadowStride = shadowMap.stride();
        args.shadowSize = 16;
        const float vp[16] = {0.2f, 0, 0, 0, 0, 0, 0.2f, 0, 0, 0.2f, 0, 0, 0, 0, 0.5f, 1};
        std::copy_n(vp, 16, args.lightViewProj);
        args.biasConst = 0.001f;
        args.biasSlope = 0.001f;
        args.pcfRadius = 1;
        args.exposure = exposure;
        for (PlaneF& p : out) p = PlaneF(w, h);
        for (int c = 0; c < 3; ++c) {
            args.color[c] = out[c].row(0);
            args.display[c] = out[3 + c].row(0);
        }
        args.shadow = out[6].row(0);
        args.outStride = out[0].stride();
        args.energy = &energyTables();
    }

    // Runs the direct kernel, with the optional parts or without.
    void shade(Isa isa, bool parts, int threads = 2) {
        const int w = frame.width, h = frame.height;
        for (int c = 0; c < 3; ++c) {
            PlaneF* groups[5] = {direct, emission, envDiffuse, envSpecular, specWeight};
            SignalOut* ptrs[5] = {args.direct, args.emission, args.envDiffuse, args.envSpecular,
                                  args.specWeight};
            for (int k = 0; k < 5; ++k) {
                groups[k][c] = PlaneF(w, h);
                ptrs[k][c] = parts ? groups[k][c].row(0) : nullptr;
            }
        }
        const auto fn = SSRT_DISPATCH(isa, shadeTile);
        parallelForTiles(TileGrid(w, h).count(), threads, [&](int t) { fn(args, t); });
    }

    // The same with f16 parts, as the renderer stores them (DirectParts).
    PlaneU16 direct16[3], emission16[3], envDiffuse16[3], envSpecular16[3], specWeight16[3];
    void shadeF16(Isa isa, int threads = 2) {
        const int w = frame.width, h = frame.height;
        for (int c = 0; c < 3; ++c) {
            PlaneU16* groups[5] = {direct16, emission16, envDiffuse16, envSpecular16, specWeight16};
            SignalOut* ptrs[5] = {args.direct, args.emission, args.envDiffuse, args.envSpecular,
                                  args.specWeight};
            for (int k = 0; k < 5; ++k) {
                groups[k][c] = PlaneU16(w, h);
                ptrs[k][c] = groups[k][c].row(0);
            }
        }
        const auto fn = SSRT_DISPATCH(isa, shadeTile);
        parallelForTiles(TileGrid(w, h).count(), threads, [&](int t) { fn(args, t); });
    }
    CompositeArgs inputsF16(float exposure) const {
        CompositeArgs in;
        for (int c = 0; c < 3; ++c) {
            in.direct[c] = viewOf(direct16[c], "direct");
            in.emission[c] = viewOf(emission16[c], "emission");
            in.envDiffuse[c] = viewOf(envDiffuse16[c], "envDiffuse");
            in.envSpecular[c] = viewOf(envSpecular16[c], "envSpecular");
            in.specWeight[c] = viewOf(specWeight16[c], "specWeight");
        }
        in.exposure = exposure;
        return in;
    }

    CompositeArgs inputs(float exposure) const {
        CompositeArgs in;
        for (int c = 0; c < 3; ++c) {
            in.direct[c] = viewOf(direct[c], "direct");
            in.emission[c] = viewOf(emission[c], "emission");
            in.envDiffuse[c] = viewOf(envDiffuse[c], "envDiffuse");
            in.envSpecular[c] = viewOf(envSpecular[c], "envSpecular");
            in.specWeight[c] = viewOf(specWeight[c], "specWeight");
        }
        in.exposure = exposure;
        return in;
    }
};

// composite() of `in` into color and display, made here at the size of in's direct parts.
void compositeInto(Isa isa, CompositeArgs in, PlaneF color[3], PlaneF display[3], int threads) {
    const FloatView& d = in.direct[0];
    const int w = d.f16 ? d.f16.width : d.f32.width, h = d.f16 ? d.f16.height : d.f32.height;
    for (int c = 0; c < 3; ++c) {
        color[c].ensureSize(w, h);
        display[c].ensureSize(w, h);
        in.color[c] = outputOf(color[c], "color");
        in.display[c] = outputOf(display[c], "display");
    }
    composite(isa, in, threads);
}

}  // namespace

TEST_CASE("composite: the direct kernel's optional parts leave color, display and shadow alone") {
    for (const char* scene : {"cornell", "spheres"}) {
        CAPTURE(scene);
        DirectFixture f(scene, 1.3f);
        f.shade(Isa::Scalar, false);
        PlaneF ref[7];
        for (int i = 0; i < 7; ++i) ref[i] = f.out[i].clone();
        for (Isa isa : supportedIsas()) {
            CAPTURE(isaName(isa));
            f.shade(isa, true);
            for (int i = 0; i < 7; ++i) CHECK(sameBits(f.out[i], ref[i]));
        }
    }
}

TEST_CASE(
    "composite: with SSR and SSGI off it rebuilds the direct kernel's color and display bit for "
    "bit") {
    for (const char* scene : {"cornell", "spheres"}) {
        for (float exposure : {1.0f, 1.3f}) {
            CAPTURE(scene);
            CAPTURE(exposure);
            DirectFixture f(scene, exposure);
            for (Isa isa : supportedIsas()) {
                CAPTURE(isaName(isa));
                f.shade(isa, true);
                for (int threads : testThreadCounts({1, 2, 8})) {
                    PlaneF color[3], display[3];
                    compositeInto(isa, f.inputs(exposure), color, display, threads);
                    for (int c = 0; c < 3; ++c) {
                        CHECK(sameBits(color[c], f.out[c]));
                        CHECK(sameBits(display[c], f.out[3 + c]));
                    }
                }
            }
        }
    }
}

// The renderer's parts are f16: each the f32 part rounded to nearest even (clamped to 65504),
// the same bits on every ISA (F16C in the avx2 and avx512 copies, integer code elsewhere), and
// the composite of them the same bits on every ISA and thread count, within f16's rounding of
// the direct kernel's own colour.
TEST_CASE("composite: f16 parts are the f32 ones rounded, the same bits on every ISA") {
    for (const char* scene : {"cornell", "spheres"}) {
        CAPTURE(scene);
        DirectFixture f(scene, 1.3f);
        f.shade(Isa::Scalar, true);
        const PlaneF* f32[5] = {f.direct, f.emission, f.envDiffuse, f.envSpecular, f.specWeight};
        const PlaneU16* f16[5] = {f.direct16, f.emission16, f.envDiffuse16, f.envSpecular16,
                                  f.specWeight16};
        PlaneF refColor[3];
        for (int c = 0; c < 3; ++c) refColor[c] = f.out[c].clone();
        PlaneF color0[3], display0[3];
        bool first = true;
        for (Isa isa : supportedIsas()) {
            CAPTURE(isaName(isa));
            f.shadeF16(isa);
            int wrong = 0;
            for (int k = 0; k < 5; ++k)
                for (int c = 0; c < 3; ++c)
                    for (int y = 0; y < f.frame.height; ++y)
                        for (int x = 0; x < f.frame.width; ++x)
                            wrong += f16[k][c].at(x, y) !=
                                     encodeF16(std::min(f32[k][c].at(x, y), 65504.0f));
            CHECK(wrong == 0);
            for (int threads : testThreadCounts({1, 2, 8})) {
                PlaneF color[3], display[3];
                compositeInto(isa, f.inputsF16(1.3f), color, display, threads);
                if (first) {
                    for (int c = 0; c < 3; ++c) {
                        color0[c] = color[c].clone();
                        display0[c] = display[c].clone();
                    }
                    first = false;
                }
                for (int c = 0; c < 3; ++c) {
                    CHECK(sameBits(color[c], color0[c]));
                    CHECK(sameBits(display[c], display0[c]));
                }
            }
        }
        // Within a few f16 ulps (2^-11 relative) of the f32 parts' colour.
        float worst = 0.0f;
        for (int c = 0; c < 3; ++c)
            for (int y = 0; y < f.frame.height; ++y)
                for (int x = 0; x < f.frame.width; ++x) {
                    const float want = refColor[c].at(x, y);
                    worst = std::max(worst, std::abs(color0[c].at(x, y) - want) /
                                                std::max(std::abs(want), 1e-3f));
                }
        MESSAGE(scene << ": largest relative difference from f32 parts " << worst);
        CHECK(worst < 4.0f / 2048.0f);
    }
}

TEST_CASE(
    "composite: specWeight is the DFG split sum F0 A + B plus Kulla-Conty's T (1 - E), every ISA") {
    DirectFixture f("spheres");
    const EnergyTables& tables = energyTables();
    for (Isa isa : supportedIsas()) {
        CAPTURE(isaName(isa));
        f.shade(isa, true);
        // Every surface pixel, E, A and B at the kernel's n.v (shade::shadeSurface).
        int checked = 0, raised = 0;
        const PlaneF& viewZ = f.frame.gbuffer.viewZ;
        const int w = f.frame.width, h = f.frame.height;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                if (viewZ.at(x, y) <= 0.0f) continue;
                const float metallic = f.frame.gbuffer.metallic.at(x, y);
                const float rough = f.frame.gbuffer.roughness.at(x, y);
                const float albedo = f.frame.gbuffer.albedo[0].at(x, y);
                const double f0 = 0.04 + (albedo - 0.04) * metallic;
                // The fixture's camera: identity rotation, view ray through the pixel centre.
                const double dx = (2.0 * (x + 0.5) / w - 1.0) * f.args.tanHalfX,
                             dy = (1.0 - 2.0 * (y + 0.5) / h) * f.args.tanHalfY, dz = -1.0;
                const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
                const double nv = -(f.frame.gbuffer.normal[0].at(x, y) * dx +
                                    f.frame.gbuffer.normal[1].at(x, y) * dy +
                                    f.frame.gbuffer.normal[2].at(x, y) * dz) /
                                  len;
                const float mu = std::max(float(nv), 1e-4f);
                const double e = multiscatter::albedo(tables, mu, rough);
                const double dfgA = multiscatter::lookup2d(tables.dfgA.data(), mu, rough);
                const double dfgB = multiscatter::lookup2d(tables.dfgB.data(), mu, rough);
                const double eAvg = multiscatter::albedoAvg(tables, rough);
                const double fAvg = f0 * 20.0 / 21.0 + 1.0 / 21.0;
                const double tint = fAvg * fAvg * eAvg / (1.0 - fAvg * (1.0 - eAvg));
                const double single = f0 * dfgA + dfgB;
                const double expected = single + tint * (1.0 - e);
                CHECK(f.specWeight[0].at(x, y) == doctest::Approx(expected).epsilon(2e-3));
                raised += f.specWeight[0].at(x, y) > 1.05 * single;
                ++checked;
            }
        CHECK(checked > 1000);
        CHECK(raised > 0);  // rough metals gain energy
    }
}

TEST_CASE("composite: SSR at opacity 0 is the sky -- at opacity 1 it replaces envSpecular") {
    DirectFixture f("spheres");
    f.shade(Isa::Scalar, true);
    const int w = f.frame.width, h = f.frame.height;
    PlaneF ref[3], refDisplay[3];
    compositeInto(Isa::Scalar, f.inputs(1.0f), ref, refDisplay, 1);
    // Opacity 0 with any finite SSR colour: the same bits as SSR off.
    PlaneF ssr[3] = {PlaneF(w, h, 5.0f), PlaneF(w, h, 6.0f), PlaneF(w, h, 7.0f)};
    PlaneF opacity(w, h, 0.0f);
    CompositeArgs in = f.inputs(1.0f);
    for (int c = 0; c < 3; ++c) in.ssrColor[c] = viewOf(ssr[c], "ssrColor");
    in.ssrOpacity = viewOf(opacity, "ssrOpacity");
    for (Isa isa : supportedIsas()) {
        PlaneF color[3], display[3];
        compositeInto(isa, in, color, display, 2);
        for (int c = 0; c < 3; ++c) CHECK(sameBits(color[c], ref[c]));
    }
    // Opacity 1 with SSR = envSpecular: the same bits again; with SSR = envSpecular + 1 the
    // colour grows by specWeight.
    opacity.fill(1.0f);
    for (int c = 0; c < 3; ++c) in.ssrColor[c] = viewOf(f.envSpecular[c], "ssrColor");
    {
        PlaneF color[3], display[3];
        compositeInto(Isa::Scalar, in, color, display, 2);
        for (int c = 0; c < 3; ++c) CHECK(sameBits(color[c], ref[c]));
    }
    PlaneF brighter[3];
    for (int c = 0; c < 3; ++c) {
        brighter[c] = f.envSpecular[c].clone();
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) brighter[c].at(x, y) += 1.0f;
        in.ssrColor[c] = viewOf(brighter[c], "ssrColor");
    }
    PlaneF color[3], display[3];
    compositeInto(Isa::Scalar, in, color, display, 2);
    for (int y = 0; y < h; y += 7)
        for (int x = 0; x < w; x += 5)
            for (int c = 0; c < 3; ++c)
                CHECK(color[c].at(x, y) ==
                      doctest::Approx(ref[c].at(x, y) + f.specWeight[c].at(x, y)).epsilon(1e-4));
}

TEST_CASE("composite: SSGI replaces envDiffuse by albedo (1 - metallic) times its radiance") {
    DirectFixture f("cornell");
    f.shade(Isa::Scalar, true);
    const int w = f.frame.width, h = f.frame.height;
    PlaneF ref[3], refDisplay[3];
    compositeInto(Isa::Scalar, f.inputs(1.0f), ref, refDisplay, 1);
    const float radiance[3] = {0.5f, 1.0f, 2.0f};
    PlaneF ssgi[3] = {PlaneF(w, h, radiance[0]), PlaneF(w, h, radiance[1]),
                      PlaneF(w, h, radiance[2])};
    CompositeArgs in = f.inputs(1.0f);
    for (int c = 0; c < 3; ++c) {
        in.ssgi[c] = viewOf(ssgi[c], "ssgi");
        in.envDiffuse[c] = {};  // not needed with SSGI on
    }
    const GBuffer& g = f.frame.gbuffer;
    in.g = g.view();
    PlaneF color[3], display[3];
    compositeInto(Isa::Scalar, in, color, display, 2);
    int surfaces = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const bool bg = g.viewZ.at(x, y) <= 0.0f;
                const float diffuse =
                    bg ? 0.0f : g.albedo[c].at(x, y) * (1.0f - g.metallic.at(x, y)) * radiance[c];
                const float expect = ref[c].at(x, y) - f.envDiffuse[c].at(x, y) + diffuse;
                CHECK(color[c].at(x, y) == doctest::Approx(expect).epsilon(1e-4));
                surfaces += bg ? 0 : 1;
            }
    CHECK(surfaces > w * h);  // most pixels are surfaces (3 channels each)
    // SSGI's diffuse colour needs the G-buffer's metallic.
    in.g.metallic = nullptr;
    CHECK_THROWS_WITH_AS(compositeInto(Isa::Scalar, in, color, display, 2),
                         "composite: metallic is missing", std::invalid_argument);
}

TEST_CASE("composite: missing planes are refused, by name") {
    CompositeArgs in;
    PlaneF color[3], display[3];
    CHECK_THROWS_WITH_AS(compositeInto(Isa::Scalar, in, color, display, 1),
                         "composite: direct is missing", std::invalid_argument);
    DirectFixture f("cornell");
    f.shade(Isa::Scalar, true);
    in = f.inputs(1.0f);
    PlaneF small(3, 3);
    in.ssgi[0] = viewOf(small, "ssgi.R");
    CHECK_THROWS_WITH_AS(compositeInto(Isa::Scalar, in, color, display, 1),
                         "composite: ssgi.R is 3x3, not 150x70", std::invalid_argument);
    // The outputs are the caller's, checked as the inputs are.
    in = f.inputs(1.0f);
    CHECK_THROWS_WITH_AS(composite(Isa::Scalar, in, 1), "composite: color is missing",
                         std::invalid_argument);
    for (int c = 0; c < 3; ++c) {
        color[c] = PlaneF(150, 70);
        display[c] = PlaneF(150, 70);
        in.color[c] = outputOf(color[c], "color");
        in.display[c] = outputOf(display[c], "display");
    }
    in.display[1] = outputOf(small, "display.G");
    CHECK_THROWS_WITH_AS(composite(Isa::Scalar, in, 1), "composite: display.G is 3x3, not 150x70",
                         std::invalid_argument);
}
