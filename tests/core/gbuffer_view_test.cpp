#include "core/gbuffer_view.h"

#include <doctest/doctest.h>

#include <stdexcept>
#include <string>

using namespace ssrt;

namespace {

// The message of the std::invalid_argument `fn` throws ("" when it throws none).
template <class Fn>
std::string refusal(Fn&& fn) {
    try {
        fn();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("G-buffer view: made from the planes given, of one size and stride") {
    const PlaneF z(10, 6, 1.0f), nx(10, 6, 0.0f), ny(10, 6, 1.0f), nz(10, 6, 0.0f), empty;
    const GBufferView g = gbufferView("pass", 10, 6,
                                      {{kGViewZ, &z},
                                       {kGNormalX, &nx},
                                       {kGNormalY, &ny},
                                       {kGNormalZ, &nz},
                                       {kGRoughness, &empty},
                                       {kGMetallic, nullptr}},
                                      kGViewZ | kGNormal);
    CHECK(g.viewZ == z.row(0));
    CHECK(g.normal[1] == ny.row(0));
    CHECK(g.stride == z.stride());
    CHECK(g.width == 10);
    CHECK(g.height == 6);
    // Empty and null planes are left out.
    CHECK(g.roughness == nullptr);
    CHECK(g.metallic == nullptr);
    CHECK(g.albedo[0] == nullptr);
    CHECK_NOTHROW(requireGBuffer("pass", g, kGViewZ | kGNormal, 10, 6));
}

TEST_CASE("G-buffer view: a plane of another size, or one a pass reads missing, is refused") {
    const PlaneF z(10, 6, 1.0f), wide(11, 6, 0.0f);
    CHECK(refusal([&] {
              gbufferView("ray generation", 10, 6, {{kGViewZ, &z}, {kGNormalY, &wide}});
          }) == "ray generation: normal.Y is 11x6, not 10x6");
    CHECK(refusal([&] {
              gbufferView("marchRays", 10, 6, {{kGViewZ, &z}}, kGViewZ | kGNormal);
          }) == "marchRays: normal.X is missing");
    const GBufferView g = gbufferView("test", 10, 6, {{kGViewZ, &z}});
    CHECK(refusal([&] { requireGBuffer("resolveSsr", g, kGViewZ | kGRoughness, 10, 6); }) ==
          "resolveSsr: roughness is missing");
    CHECK(refusal([&] { requireGBuffer("resolveSsr", g, kGViewZ, 12, 6); }) ==
          "resolveSsr: the G-buffer is 10x6, not 12x6");
    CHECK(refusal([&] { requireGBuffer("resolveSsr", g, kGViewZ, 10, 6); }).empty());
}

TEST_CASE("G-buffer planes: one list, walked in bit order, a mask choosing the planes") {
    // Every plane once, in GBufferPlane's order, each at its own member.
    GBufferOf<int> g;
    int next = 0;
    GBufferOf<int>::forEach(g, [&](GBufferPlane which, int& p) {
        CHECK(which == GBufferPlane(1u << next));
        p = ++next;
    });
    CHECK(next == kGBufferPlaneCount);
    CHECK(g.viewZ == 1);
    CHECK(g.normal[2] == 4);
    CHECK(g.albedo[0] == 5);
    CHECK(g.roughness == 9);
    CHECK(g.motion[1] == 12);
    CHECK(g.emission[0] == 13);
    CHECK(g.triangleId == 18);
    for (int i = 0; i < kGBufferPlaneCount; ++i)
        CHECK(GBufferOf<int>::at(g, GBufferPlane(1u << i)) == i + 1);
    // A mask walks its planes alone.
    GBufferPlanes seen = 0;
    GBufferOf<int>::forEach(
        g, [&](GBufferPlane which, int&) { seen |= which; }, kGNormal | kGMotion);
    CHECK(seen == (kGNormal | kGMotion));
}

TEST_CASE("G-buffer planes: a holder's names are its prefix and the plane's, kept for good") {
    const std::string_view a = gbufferPlaneName("half.guide.", kGNormalY);
    CHECK(a == "half.guide.normal.Y");
    CHECK(gbufferPlaneName("half.guide.", kGNormalY).data() == a.data());  // made once
    CHECK(gbufferPlaneName("", kGMotionX) == "motion.X");
    CHECK(gbufferPlaneName("history.", kGTriangleId) == "history.triangleId");
}

TEST_CASE("G-buffer view: the planes of one view taken into another of the same size") {
    const PlaneF z(10, 6, 1.0f), a(10, 6, 0.5f), m(10, 6, 0.0f), other(12, 6, 0.0f);
    const GBufferView guides = gbufferView("test", 10, 6, {{kGViewZ, &z}});
    const GBufferView frame = gbufferView("test", 10, 6, {{kGAlbedoG, &a}, {kGMetallic, &m}});
    const GBufferView both = withPlanes(guides, frame, kGAlbedo | kGMetallic);
    CHECK(both.viewZ == z.row(0));
    CHECK(both.albedo[1] == a.row(0));
    CHECK(both.albedo[0] == nullptr);
    CHECK(both.metallic == m.row(0));
    const GBufferView wide = gbufferView("test", 12, 6, {{kGMetallic, &other}});
    CHECK(refusal([&] { withPlanes(guides, wide, kGMetallic); }) ==
          "withPlanes: G-buffer views of different sizes or strides");
}
