// The whole-scene white furnace: a white (baseColor 1), fully metallic sphere under a constant
// white sky (intensity 1), the sun off, exposure 1. F = 1 everywhere (Schlick with F0 = 1),
// the sky is 1 in every direction, so the specular albedo with multiple scattering is 1 and
// every sphere pixel of `color` must be 1 (Kulla and Conty 2017; shading/direct_lanes.h). The
// tolerance, 1 %, covers the tables' interpolation, not a missing term: single scattering alone
// loses up to about 60 % at roughness 1 (tests/shading/multiscatter_test.cpp).
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdio>

#include "renderer/renderer.h"
#include "scenes/mesh_builders.h"

using namespace ssrt;

namespace {

Scene furnaceScene(float roughness) {
    Scene s;
    s.meshes.push_back(makeUvSphere(1.0f, 64, 32));
    Material m;
    m.baseColor = glm::vec3(1.0f);
    m.metallic = 1.0f;
    m.roughness = roughness;
    s.materials.push_back(m);
    s.instances.push_back(Instance{});
    s.sky.kind = Sky::Kind::Constant;
    s.sky.zenith = glm::vec3(1.0f);
    s.sky.intensity = 1.0f;
    s.light.intensity = 0.0f;
    s.camera.position = {0.0f, 0.0f, 3.5f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.previousCamera = s.camera;
    return s;
}

// The smallest and largest colour value over the sphere's pixels (all three channels).
struct Range {
    float lo = 1e30f, hi = -1e30f;
    int pixels = 0;
};

Range sphereRange(const Frame& f) {
    Range r;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            if (f.gbuffer.viewZ.at(x, y) <= 0.0f) continue;
            ++r.pixels;
            for (int c = 0; c < 3; ++c) {
                r.lo = std::min(r.lo, f.rgb(Res::Color)[c].at(x, y));
                r.hi = std::max(r.hi, f.rgb(Res::Color)[c].at(x, y));
            }
        }
    return r;
}

void checkFurnace(bool trace) {
    for (float roughness : {0.05f, 0.25f, 0.5f, 0.75f, 1.0f}) {
        CAPTURE(roughness);
        RenderSettings rs;
        rs.width = 96;
        rs.height = 64;
        rs.shadowMapSize = 64;
        rs.exposure = 1.0f;
        rs.trace.ssr = rs.trace.ssgi = trace;
        const Frame f = Renderer(rs).renderWithoutHistory(furnaceScene(roughness));
        const Range r = sphereRange(f);
        std::printf("white furnace (trace %s) roughness %.2f: color in [%.5f, %.5f] over %d px\n",
                    trace ? "on" : "off", roughness, r.lo, r.hi, r.pixels);
        REQUIRE(r.pixels > 1000);
        CHECK(r.lo >= 0.99f);
        CHECK(r.hi <= 1.01f);
    }
}

}  // namespace

TEST_CASE("white furnace: a white rough metal sphere under a white sky is 1 +- 1 %, no trace") {
    checkFurnace(false);
}

TEST_CASE("white furnace: the same with SSR and SSGI on (the default path)") { checkFurnace(true); }
