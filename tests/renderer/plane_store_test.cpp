#include "renderer/plane_store.h"

#include <doctest/doctest.h>

#include <set>
#include <stdexcept>
#include <string>

using namespace ssrt;

TEST_CASE("plane store: the frame's outputs are every output outside the G-buffer, by resource") {
    const PlaneStore s = PlaneStore::frameOutputs();
    int held = 0;
    for (int r = 0; r < kResourceCount; ++r) {
        const Res id = Res(r);
        const ResourceDecl& d = resourceDecl(id);
        CAPTURE(std::string(d.name));
        const bool output = d.lifetime == Lifetime::Output && d.group != LayerGroup::GBuffer;
        CHECK(s.holds(id) == output);
        if (!output) {
            CHECK_THROWS_AS(s.planes(id), std::logic_error);
            continue;
        }
        ++held;
        CHECK(d.format == PixelFormat::F32);
        // Each channel its own plane, empty until a pass sizes it.
        std::set<const PlaneF*> distinct;
        for (int ch = 0; ch < d.channelCount(); ++ch) {
            CHECK(s.plane(id, ch).empty());
            distinct.insert(&s.plane(id, ch));
            CHECK(&s.plane(id, ch) == s.planes(id) + ch);
        }
        CHECK(int(distinct.size()) == d.channelCount());
        CHECK_THROWS_AS(s.plane(id, d.channelCount()), std::logic_error);
        if (d.channelCount() == 3) CHECK(&s.rgb(id)[2] == &s.plane(id, 2));
        else CHECK_THROWS_AS(s.rgb(id), std::logic_error);
    }
    CHECK(s.holds(Res::Color));
    CHECK(s.holds(Res::SsrOpacity));
    CHECK(s.holds(Res::DenoisedSpecular));  // (the denoiser writes into the frame's)
    CHECK_FALSE(s.holds(Res::Normal));      // (the G-buffer's)
    CHECK(held >= 16);
}

TEST_CASE("plane store: planes are written and viewed under the table's names, by group") {
    PlaneStore s = PlaneStore::frameOutputs();
    const OutF out = s.output(Res::Ssr, 1, 4, 3);
    REQUIRE(out.data != nullptr);
    CHECK(s.plane(Res::Ssr, 1).width() == 4);
    CHECK(s.plane(Res::Ssr, 1).height() == 3);
    out.data[0] = 2.5f;
    const ViewF in = s.view(Res::Ssr, 1);
    CHECK(in.data[0] == 2.5f);
    CHECK(in.name == channelName(Res::Ssr, 1));
    // The colour group is the image's three resources; the trace group begins with SSR's and
    // ends with the denoiser's (the file's layer order).
    std::string names;
    s.forEachPlane(LayerGroup::Color,
                   [&](std::string_view n, const PlaneF&) { names += std::string(n) + " "; });
    CHECK(names == "color.R color.G color.B display.R display.G display.B shadow ");
    std::string first, last;
    s.forEachPlane(LayerGroup::Trace, [&](std::string_view n, const PlaneF&) {
        if (first.empty()) first = n;
        last = n;
    });
    CHECK(first == "ssr.R");
    CHECK(last == "specularFrames");
}

TEST_CASE("plane store: a store of chosen resources holds those alone, f32 only") {
    PlaneStore half{Res::HalfDenoised, Res::HalfDiffuseFrames};
    CHECK(half.holds(Res::HalfDenoised));
    CHECK_FALSE(half.holds(Res::DenoisedDiffuse));
    CHECK_THROWS_AS(half.plane(Res::DenoisedDiffuse), std::logic_error);
    std::string names;
    half.forEachPlane([&](std::string_view n, const PlaneF&) { names += std::string(n) + " "; });
    CHECK(names ==
          "half.denoisedDiffuse.R half.denoisedDiffuse.G half.denoisedDiffuse.B "
          "half.diffuseFrames ");
    // (The ids are u32, the denoiser's signals f16: not a store's.)
    CHECK_THROWS_AS(PlaneStore{Res::VisibilityIds}, std::logic_error);
}
