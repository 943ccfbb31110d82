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
