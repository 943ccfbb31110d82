#include "renderer/output_store.h"

#include <doctest/doctest.h>

#include <set>
#include <stdexcept>
#include <string>

using namespace ssrt;

TEST_CASE(
    "output store: every f32 output outside the G-buffer, one plane per channel, by resource") {
    OutputStore s;
    int held = 0;
    for (int r = 0; r < kResourceCount; ++r) {
        const Res id = Res(r);
        const ResourceDecl& d = resourceDecl(id);
        CAPTURE(std::string(d.name));
        if (!OutputStore::holds(id)) {
            CHECK_THROWS_AS(s.planes(id), std::logic_error);
            continue;
        }
        ++held;
        CHECK(d.lifetime == Lifetime::Output);
        CHECK(d.group != LayerGroup::GBuffer);
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
    CHECK(OutputStore::holds(Res::Color));
    CHECK(OutputStore::holds(Res::SsrOpacity));
    CHECK_FALSE(OutputStore::holds(Res::Normal));  // (the G-buffer's)
    CHECK(held >= 12);
}

TEST_CASE("output store: planes are written and viewed under the table's names, by group") {
    OutputStore s;
    const OutF out = s.output(Res::Ssr, 1, 4, 3);
    REQUIRE(out.data != nullptr);
    CHECK(s.plane(Res::Ssr, 1).width() == 4);
    CHECK(s.plane(Res::Ssr, 1).height() == 3);
    out.data[0] = 2.5f;
    const ViewF in = s.view(Res::Ssr, 1);
    CHECK(in.data[0] == 2.5f);
    CHECK(in.name == channelName(Res::Ssr, 1));
    // The colour group is the image's three resources; the trace group begins with SSR's.
    std::string names;
    s.forEachPlane(LayerGroup::Color,
                   [&](std::string_view n, const PlaneF&) { names += std::string(n) + " "; });
    CHECK(names == "color.R color.G color.B display.R display.G display.B shadow ");
    std::string first;
    s.forEachPlane(LayerGroup::Trace, [&](std::string_view n, const PlaneF&) {
        if (first.empty()) first = n;
    });
    CHECK(first == "ssr.R");
}
