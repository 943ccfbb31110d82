// The reference cache key of fixed settings, pinned: the field table (renderer/settings_fields.h)
// drives hashRender, and a cache key must not move when the code that computes it does (only
// when kReferenceVersion is bumped for a new model: version 2, the Kulla-Conty specular; 3,
// positions from the scene's origin; 4, primary hits from the near plane; 5, the shadow map's
// receiver-plane PCF).
#include <doctest/doctest.h>

#include "scenes/builtin_scenes.h"
#include "truth/reference_image.h"

using namespace ssrt;

TEST_CASE("settings fields: the reference key of today's settings is unchanged") {
    const Scene scene = makeBuiltinScene("cornell");
    RenderSettings rs;
    const ReferenceSettings ref;
    const uint64_t defaults = referenceKey(scene, scene.camera, 0, rs, ref);
    rs.width = 320, rs.height = 180, rs.shadowMapSize = 512, rs.shadowBias = 0.75f;
    rs.shadowSlopeBias = 3.0f, rs.pcfRadius = 2, rs.exposure = 1.5f;
    rs.trace.ssrMethod = SsrMethod::GgxNdf;
    const uint64_t edited = referenceKey(scene, scene.camera, 9, rs, ref);
    CHECK(defaults == 2469946427571681638ull);
    CHECK(edited == 14415513622735101243ull);
}
