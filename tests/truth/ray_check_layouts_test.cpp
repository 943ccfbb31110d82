// Ray checks of the trace layouts (trace/trace_layout.h): the half-resolution layout's SSGI
// rays, marched on the half frame, are checked from their own origins and judged in the
// frame's pixels, so that their classes are those of the full layout's rays where both leave
// from the same surface.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <vector>

#include "renderer/renderer.h"
#include "scenes/builtin_scenes.h"
#include "scenes/scene_helpers.h"
#include "trace/march.h"
#include "truth/ray_check.h"

using namespace ssrt;

namespace {

// The cornell box seen level, straight at its back wall: a wall facing the camera has one
// depth, so the half frame's ray leaving from its block's centre at the chosen pixel's depth
// leaves from the wall itself, as the full layout's does. (Elsewhere the half frame's origins
// lie up to half a full pixel's depth slope off their surface, which Embree sees: the layouts'
// classes differ there by more than sampling.)
constexpr int kBackWall = 1;  // the back wall's instance (scenes/builtin_scenes.cpp)

Scene levelCornell() {
    Scene scene = makeBuiltinScene("cornell");
    helpers::setCamera(scene, helpers::makeCamera({0.0f, 1.0f, 3.2f}, {0.0f, 1.0f, 0.0f}, 40.0f));
    return scene;
}

struct LayoutCheck {
    RayCheckTable table;  // every SSGI ray
    CheckPlanes planes;   // sample 0's, in the frame's pixels
    Frame frame;
    std::vector<std::array<int, 2>> chosen;  // the frame pixels the half frame's rays stand for
};

// Renders `scene` at 320x180 with SSGI in `layout` (SSR off) and checks its rays as
// `ssrt compare` does.
LayoutCheck checkSsgi(const Scene& scene, const EmbreeScene& embree, TraceLayout layout) {
    RenderSettings rs;
    rs.width = 320;
    rs.height = 180;
    rs.shadowMapSize = 512;
    rs.trace.ssr = false;
    rs.trace.ssgiLayout = layout;
    RayCheckSettings cs;
    cs.maxDistance = marchLengths(rs.trace.march, scene.diagonal()).maxDistance;
    LayoutCheck out;
    const TraceObserver check = [&](TracePass, int, const RayBatch& rays, const MarchResult& march,
                                    const HalfFrame* half) {
        out.table.add(checkRays(embree, out.frame.camera, out.frame.gbuffer.viewZ, rays, march, cs,
                                out.planes.data(), 0, half));
        if (!half) return;
        for (int y = 0; y < rays.height(); ++y)
            for (int x = 0; x < rays.width(); ++x)
                if (rays.pdf.at(x, y) > 0.0f) {
                    const PixelOffset p = halfSource(x, y, half->offset, rs.width, rs.height);
                    out.chosen.push_back({p.x, p.y});
                }
    };
    Renderer(rs).renderWithoutHistory(scene, FrameInput::still(scene), out.frame, &check);
    out.table.finish();
    return out;
}

// Class shares (0..1) of the rays leaving from the back wall, from the per-pixel planes.
std::array<double, kRayClassCount> backWallShares(const LayoutCheck& c, uint64_t& rays) {
    std::array<uint64_t, kRayClassCount> n{};
    rays = 0;
    const PlaneF& ids = c.frame.gbuffer.instanceId;
    REQUIRE(c.planes[kCheckClass].width() == ids.width());
    for (int y = 0; y < ids.height(); ++y)
        for (int x = 0; x < ids.width(); ++x) {
            const int cls = int(c.planes[kCheckClass].at(x, y));
            if (cls == int(RayClass::NoRay) || int(ids.at(x, y)) != kBackWall) continue;
            ++n[std::size_t(cls)];
            ++rays;
        }
    std::array<double, kRayClassCount> share{};
    for (int i = 0; i < kRayClassCount; ++i) share[std::size_t(i)] = double(n[i]) / double(rays);
    return share;
}

}  // namespace

TEST_CASE("ray check: the half layout's SSGI rays are all checked, each at its chosen pixel") {
    const Scene scene = levelCornell();
    const EmbreeScene embree(scene);
    const LayoutCheck half = checkSsgi(scene, embree, TraceLayout::Half);
    const TraceStats& st = half.frame.stats.ssgi;
    REQUIRE(half.table.rays > 0);
    CHECK(half.table.rays == st.march.rays);
    uint64_t classified = 0;
    for (int c = 1; c < kRayClassCount; ++c) classified += half.table.count[std::size_t(c)];
    CHECK(classified == half.table.rays);
    // The planes hold a class exactly at the chosen pixels of the rays (NoRay elsewhere).
    uint64_t marked = 0;
    for (int y = 0; y < half.planes[kCheckClass].height(); ++y)
        for (int x = 0; x < half.planes[kCheckClass].width(); ++x)
            marked += half.planes[kCheckClass].at(x, y) != float(int(RayClass::NoRay));
    CHECK(marked == half.table.rays);
    uint64_t misplaced = 0;
    for (const auto& p : half.chosen) misplaced += half.planes[kCheckClass].at(p[0], p[1]) == 0.0f;
    CHECK(misplaced == 0);
}

// The two layouts draw other random rays from other pixels (a quarter of them for half), so
// their shares are two samples of one distribution: on the back wall's ~3800 half-layout
// rays a share's standard error is at most sqrt(0.25 / 3800) = 0.8 points, so 4 points (5
// standard errors) for each class. Agreed and false hit may trade more between them: the
// half depth buffer holds a surface at half the resolution, so its hits lie a little further
// from the true ones (on this wall 5.1 % of the half layout's rays are false hits against
// 1.3 % of the full one's since the rays start at the chosen pixels (6.7 % before); their
// pixel errors are just past the 2-pixel tolerance) while the march's hit share (their sum)
// stays within 4 points; 8 points for each. Without the march's hits moved into the frame's pixels
// they are about 2x off and the agreed share drops to near 0.
TEST_CASE("ray check: on a wall facing the camera the half layout's classes are the full one's") {
    const Scene scene = levelCornell();
    const EmbreeScene embree(scene);
    uint64_t fullRays = 0, halfRays = 0;
    const auto full = backWallShares(checkSsgi(scene, embree, TraceLayout::Full), fullRays);
    const auto half = backWallShares(checkSsgi(scene, embree, TraceLayout::Half), halfRays);
    REQUIRE(halfRays > 1000);
    CHECK(fullRays > 3 * halfRays);
    const auto diff = [&](RayClass c) { return std::abs(full[int(c)] - half[int(c)]); };
    for (int c = 1; c < kRayClassCount; ++c) {
        const RayClass rc = RayClass(c);
        CAPTURE(rayClassName(rc));
        CAPTURE(full[std::size_t(c)]);
        CAPTURE(half[std::size_t(c)]);
        const bool traded = rc == RayClass::Agreed || rc == RayClass::FalseHit;
        CHECK(diff(rc) <= (traded ? 0.08 : 0.04));
    }
    const auto hits = [](const std::array<double, kRayClassCount>& s) {
        return s[int(RayClass::Agreed)] + s[int(RayClass::FalseHit)];
    };
    CHECK(std::abs(hits(full) - hits(half)) <= 0.04);
    CHECK(half[int(RayClass::Agreed)] > 0.2);
}
