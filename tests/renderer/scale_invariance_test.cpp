// Any unit and any position (DESIGN.md; issue 16 item 1): a built-in scene scaled by 1e-3 and
// 1e3, or moved 1e4 units from the origin (camera too), renders the same image as the
// original, for every marcher: no length in the renderer is absolute (the march's lengths
// are relative to depth and to the scene's diagonal; world positions are measured from the
// scene's centre).
#include <doctest/doctest.h>

#include <string>

#include "renderer/renderer.h"
#include "scene_transforms.h"
#include "truth/image_error.h"

using namespace ssrt;
using namespace ssrt::test;

namespace {

RenderSettings small(Marcher m) {
    RenderSettings rs;
    rs.width = 160;
    rs.height = 90;
    rs.shadowMapSize = 512;
    rs.threads = 2;
    rs.trace.marcher = m;
    return rs;
}

double colourError(const Frame& f, const Frame& ref) {
    const auto imgRgb = f.rgb(Res::Color);
    const PlaneF* img[3] = {&imgRgb[0], &imgRgb[1], &imgRgb[2]};
    const auto rRgb = ref.rgb(Res::Color);
    const PlaneF* r[3] = {&rRgb[0], &rRgb[1], &rRgb[2]};
    return imageError(img, r).relMse;
}

constexpr double kBar = 1e-3;  // issue 16: relMSE of the colour

}  // namespace

TEST_CASE("renderer: scale invariance, scenes scaled by 1e-3 and 1e3 and moved 1e4") {
    for (const std::string name : {"cornell", "spheres", "corridor"}) {
        for (const Marcher m : {Marcher::Linear, Marcher::Dda, Marcher::HiZ}) {
            CAPTURE(name);
            CAPTURE(marcherName(m));
            const Renderer r(small(m));
            const Frame base = r.renderWithoutHistory(makeBuiltinScene(name));
            const double small =
                colourError(r.renderWithoutHistory(scaledScene(name, 1e-3f)), base);
            const double large = colourError(r.renderWithoutHistory(scaledScene(name, 1e3f)), base);
            CHECK(small <= kBar);
            CHECK(large <= kBar);
            // Moved: against the same scene brought back to 0 exactly (what the renderer
            // adds), and against the unmoved one (adding the input's own rounding).
            const Scene moved = movedScene(name);
            const Frame far = r.renderWithoutHistory(moved);
            const double added = colourError(far, r.renderWithoutHistory(movedBack(moved)));
            const double total = colourError(far, base);
            CHECK(added <= kBar);
            MESSAGE(name << " " << marcherName(m) << ": colour relMSE scaled 1e-3 " << small
                         << ", 1e3 " << large << "; moved 1e4 " << added
                         << " (against the unmoved scene " << total
                         << ", of which the move's float rounding is the rest)");
        }
    }
}

TEST_CASE("renderer: scale invariance of the direct light alone (no trace)") {
    for (const std::string name : {"cornell", "spheres", "corridor"}) {
        CAPTURE(name);
        RenderSettings rs = small(Marcher::HiZ);
        rs.trace.ssr = rs.trace.ssgi = false;
        const Renderer r(rs);
        const Frame base = r.renderWithoutHistory(makeBuiltinScene(name));
        // Scaled: only rounding moves (relMSE ~1e-11).
        CHECK(colourError(r.renderWithoutHistory(scaledScene(name, 1e-3f)), base) <= 1e-9);
        CHECK(colourError(r.renderWithoutHistory(scaledScene(name, 1e3f)), base) <= 1e-9);
        const Scene moved = movedScene(name);
        const double added =
            colourError(r.renderWithoutHistory(moved), r.renderWithoutHistory(movedBack(moved)));
        CHECK(added <= 1e-4);
        MESSAGE(name << " direct only, moved 1e4: relMSE " << added);
    }
}
