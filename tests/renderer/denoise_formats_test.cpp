// The resource table (renderer/resources.cpp) declares each resource's format, from which
// `ssrt graph` and --stats' declared memory count bytes; the denoiser's planes (denoise/denoise.h)
// hold what they hold in the element type they were given. This holds the two together: every
// plane of the denoiser's scratch and history names a channel of the table (its full-resolution
// name, and with "half." / "history.half." its half frame's), whose format takes as many bytes
// a texel as the plane's element. A plane moved to another format without its declaration (or
// the reverse) fails here.
#include <doctest/doctest.h>

#include <string>
#include <string_view>

#include "core/pixel_formats.h"
#include "denoise/denoise.h"
#include "renderer/resources.h"

using namespace ssrt;

namespace {

// The half frame's history resources: the guides and speeds in one, the signal and the fast
// history each in its own.
std::string halfHistoryName(std::string_view full) {
    const std::string_view guide = "history.denoise.guide.";
    if (full.starts_with(guide))
        return "history.half.denoise." + std::string(full.substr(guide.size()));
    if (full == "history.denoise.diffuse") return "history.half.denoise.diffuse";
    if (full == "history.denoise.diffuseFast") return "history.half.denoise.diffuseFast";
    if (full == "history.denoise.diffuseFrames") return "history.half.denoise.frames";
    return "";
}

template <class Group>
int checkGroup(const Group& group, bool half, bool history) {
    int planes = 0;
    group.forEachPlane([&](std::string_view name, const auto& plane) {
        std::string channel(name);
        if (half && name.find("specular") != std::string_view::npos) return;  // (diffuse only)
        if (half) channel = history ? halfHistoryName(name) : "half." + channel;
        if (channel.empty()) return;
        CAPTURE(channel);
        const Res res = resourceOfChannel(channel);
        REQUIRE(res != Res::Count);
        const ResourceDecl& d = resourceDecl(res);
        CAPTURE(pixelFormatName(d.format));
        CHECK(bytesPerTexel(d.format) == int(sizeof(*plane.row(0))));
        CHECK(d.lifetime == (history ? Lifetime::History : Lifetime::Transient));
        CHECK(d.resolution == (half ? Resolution::Half : Resolution::Full));
        ++planes;
    });
    return planes;
}

}  // namespace

TEST_CASE(
    "denoise formats: each plane of the denoiser's scratch and history is declared in the "
    "resource table with its element's size") {
    const DenoiseScratch scratch;
    const DenoiseHistory history;
    CHECK(checkGroup(scratch, false, false) == 16);
    CHECK(checkGroup(history, false, true) == 11);
    CHECK(checkGroup(scratch, true, false) == 8);
    CHECK(checkGroup(history, true, true) == 8);
    // The signals are f16, radiance with hit distance packed as 4 x f16 a pixel (issue 44), the
    // fast luma f16 alone, and the guides f32.
    CHECK(resourceDecl(resourceOfChannel("blurred.specular")).format == PixelFormat::F16x4);
    CHECK(resourceDecl(resourceOfChannel("history.denoise.diffuse")).format == PixelFormat::F16x4);
    CHECK(resourceDecl(resourceOfChannel("fast.diffuse")).format == PixelFormat::F16);
    CHECK(resourceDecl(resourceOfChannel("history.denoise.guide.viewZ")).format ==
          PixelFormat::F32);
}
