// The reference's shading against the direct pass: the same model at the G-buffer's points
// and at Embree's hits, and what changes with Embree's visibility.
#include "world/hit_light.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/pixel_formats.h"
#include "material_maps.h"
#include "renderer/direct_lighting.h"
#include "tests/truth/reference_test_rig.h"
#include "truth/reference_image.h"

using namespace ssrt;
using test::ReferenceRig;

namespace {

float relDiff(float a, float b) { return std::abs(a - b) / std::max(std::abs(b), 1e-6f); }

// The frame's lighting with its G-buffer and camera, as the reference sets it up.
void frameLighting(const ReferenceRig& rig, DirectLighting& l) {
    setDirectLighting(rig.scene, rig.renderer.settings(), rig.frame.scratch.shadow, nullptr, l);
    DirectArgs& a = l.args;
    setDirectGBuffer(rig.frame.gbuffer, a);
    a.width = rig.frame.width;
    a.height = rig.frame.height;
    a.tanHalfX = rig.frame.camera.tanHalfX;
    a.tanHalfY = rig.frame.camera.tanHalfY;
    std::copy_n(rig.frame.camera.viewToWorld, 9, a.viewToWorld);
    std::copy_n(rig.frame.camera.position, 3, a.camPos);
}

}  // namespace

// (The direct pass stores its parts in f16: the reference's part, rounded as it stores it.)
TEST_CASE("reference: with the shadow map, its direct part is the direct pass's to the bit") {
    for (const char* name : {"cornell", "spheres"}) {
        const ReferenceRig rig(name);
        const ReferenceImage ref = rig.reference(1, ReferenceSettings::Visibility::ShadowMap);
        int surface = 0, differ = 0;
        for (int y = 0; y < rig.frame.height; ++y)
            for (int x = 0; x < rig.frame.width; ++x) {
                surface += rig.frame.gbuffer.viewZ.at(x, y) > 0.0f;
                for (int c = 0; c < 3; ++c)
                    differ += encodeF16(std::min(ref.direct[c].at(x, y), 65504.0f)) !=
                              rig.frame.direct.direct[c].at(x, y);
            }
        MESSAGE(std::string(name) << ": " << surface << " surface pixels, " << differ
                                  << " channels differ");
        CHECK(surface > 1000);
        CHECK(differ == 0);
    }
}

TEST_CASE("reference: a hit seen from the camera shades like the direct pass's pixel") {
    // Frame without trace passes: its colour is the direct pass's own (exposure 1), the model
    // hitRadiance evaluates at Embree's hits. The two points differ by the raster's
    // reconstruction (float rounding), so a few pixels may flip a PCF tap: most pixels agree
    // tightly, nearly all within 1e-3.
    const ReferenceRig rig("cornell", 96, 54, 0, false);
    DirectLighting lighting;
    frameLighting(rig, lighting);
    const worldhit::ShadingContext ctx{&lighting.args, &rig.embree,
                                       ReferenceSettings::Visibility::ShadowMap};
    const glm::vec3 cam(rig.frame.camera.position[0], rig.frame.camera.position[1],
                        rig.frame.camera.position[2]);
    std::vector<float> errors;
    for (int y = 0; y < rig.frame.height; ++y)
        for (int x = 0; x < rig.frame.width; ++x) {
            if (!(rig.frame.gbuffer.viewZ.at(x, y) > 0.0f)) continue;
            const worldhit::PointSurface ps = worldhit::pixelSurface(lighting.args, x, y);
            const glm::vec3 dir = -glm::vec3(ps.view.x, ps.view.y, ps.view.z);
            const EmbreeHit hit = rig.embree.intersect(cam, dir, 0.0f, 1e30f);
            REQUIRE(hit.hit);
            const glm::vec3 l = worldhit::hitRadiance(ctx, cam, dir, hit, true);
            float e = 0.0f;
            for (int c = 0; c < 3; ++c)
                e = std::max(e, relDiff(l[c], rig.frame.rgb(Res::Color)[c].at(x, y)));
            errors.push_back(e);
        }
    std::sort(errors.begin(), errors.end());
    const float median = errors[errors.size() / 2], p99 = errors[errors.size() * 99 / 100];
    MESSAGE("relative error: median " << median << ", 99th percentile " << p99 << ", max "
                                      << errors.back() << " over " << errors.size() << " pixels");
    CHECK(median < 1e-4f);
    CHECK(p99 < 1e-3f);
}

TEST_CASE("reference: Embree's visibility differs from the shadow map's only where that errs") {
    // Sun part = (diffuse + specular) E (n.l visibility): with visibility 1 or 0 from Embree
    // against the shadow map's PCF fraction v, the Embree part is 0 or at least the shadow
    // map's (v <= 1, rounding is monotone), and equal to the bit where v = 1 and Embree agrees.
    // Disagreements outside penumbrae are the shadow map's errors (bias, resolution): few.
    const ReferenceRig rig("cornell");
    const ReferenceImage sm = rig.reference(1, ReferenceSettings::Visibility::ShadowMap);
    const ReferenceImage em = rig.reference(1, ReferenceSettings::Visibility::Embree);
    const PlaneF& v = rig.frame.plane(Res::Shadow);
    int hard = 0, hardDisagree = 0, bothLit = 0, bothDark = 0;
    for (int y = 0; y < rig.frame.height; ++y)
        for (int x = 0; x < rig.frame.width; ++x) {
            if (!(rig.frame.gbuffer.viewZ.at(x, y) > 0.0f)) continue;
            bool zero = true, equal = true;
            for (int c = 0; c < 3; ++c) {
                const float e = em.direct[c].at(x, y), s = sm.direct[c].at(x, y);
                zero = zero && e == 0.0f;
                equal = equal && e == s;
                CHECK((e == 0.0f || e >= s));
            }
            if (v.at(x, y) != 0.0f && v.at(x, y) != 1.0f) continue;
            ++hard;
            const bool agree = v.at(x, y) == 1.0f ? equal : zero;
            hardDisagree += !agree;
            bothLit += agree && v.at(x, y) == 1.0f && !zero;
            bothDark += agree && v.at(x, y) == 0.0f;
        }
    MESSAGE(hard << " pixels with a hard shadow-map answer: " << bothLit << " lit and " << bothDark
                 << " dark in both, " << hardDisagree << " where Embree disagrees");
    CHECK(bothLit > hard / 10);
    CHECK(bothDark > 0);
    CHECK(hardDisagree < hard / 20);
}

TEST_CASE("reference: normal, occlusion and emissive maps shade its hits as the raster's pixels") {
    // cornell with every material's maps (tests/material_maps.h), traced passes on so the
    // frame hands out its parts. At Embree's hit through each pixel the truth reads the maps
    // itself (level 0, bilinear; the maps are magnified so the raster reads level 0 too) and
    // bends its own normal with its own tangents: its full radiance must be the pixel's
    // direct-pass sum, and its SSGI radiance (Lambert sun + emission) the pixel's hitLight.
    Scene scene = makeBuiltinScene("cornell");
    test::addMaterialMaps(scene);
    const Renderer renderer(test::referenceRigSettings(96, 54, 0, true));
    const Frame frame = renderer.renderWithoutHistory(scene);
    const EmbreeScene embree(scene);
    DirectLighting lighting;
    setDirectLighting(scene, renderer.settings(), frame.scratch.shadow, nullptr, lighting);
    DirectArgs& a = lighting.args;
    setDirectGBuffer(frame.gbuffer, a);
    a.width = frame.width;
    a.height = frame.height;
    a.tanHalfX = frame.camera.tanHalfX;
    a.tanHalfY = frame.camera.tanHalfY;
    std::copy_n(frame.camera.viewToWorld, 9, a.viewToWorld);
    std::copy_n(frame.camera.position, 3, a.camPos);
    const worldhit::ShadingContext ctx{&a, &embree, ReferenceSettings::Visibility::ShadowMap};
    const glm::vec3 cam(frame.camera.position[0], frame.camera.position[1],
                        frame.camera.position[2]);
    const DirectParts& p = frame.direct;
    // The direct pass's own colour, its parts' sum in f32 (the frame's parts are f16): the
    // frame without trace passes (the direct pass is the same).
    RenderSettings noTrace = renderer.settings();
    noTrace.trace.ssr = noTrace.trace.ssgi = false;
    const Frame withoutTrace = Renderer(noTrace).renderWithoutHistory(scene);
    REQUIRE(withoutTrace.direct.direct[0].empty());
    const float exposure = noTrace.exposure;
    std::vector<float> full, bounce;
    int occluded = 0, emitting = 0;
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) {
            if (!(frame.gbuffer.viewZ.at(x, y) > 0.0f)) continue;
            const worldhit::PointSurface ps = worldhit::pixelSurface(a, x, y);
            const glm::vec3 dir = -glm::vec3(ps.view.x, ps.view.y, ps.view.z);
            const EmbreeHit hit = embree.intersect(cam, dir, 0.0f, 1e30f);
            REQUIRE(hit.hit);
            const glm::vec3 lf = worldhit::hitRadiance(ctx, cam, dir, hit, true);
            const glm::vec3 lb = worldhit::hitRadiance(ctx, cam, dir, hit, false);
            float ef = 0.0f, eb = 0.0f;
            for (int c = 0; c < 3; ++c) {
                const float sum = withoutTrace.rgb(Res::Color)[c].at(x, y) / exposure;
                ef = std::max(ef, relDiff(lf[c], sum));
                // (The hit light against the model's rounded as the direct pass stores it.)
                eb = std::max(
                    eb, relDiff(decodeF16(encodeF16(lb[c])), decodeF16(p.hitLight[c].at(x, y))));
            }
            full.push_back(ef);
            bounce.push_back(eb);
            occluded += frame.gbuffer.occlusion.at(x, y) < 0.9f;
            emitting += frame.gbuffer.emission[0].at(x, y) > 0.0f;
        }
    for (std::vector<float>* e : {&full, &bounce}) {
        std::sort(e->begin(), e->end());
        const float median = (*e)[e->size() / 2], p99 = (*e)[e->size() * 99 / 100];
        MESSAGE((e == &full ? "full" : "SSGI")
                << " radiance, relative error: median " << median << ", 99th percentile " << p99
                << " over " << e->size() << " pixels");
        CHECK(median < 1e-4f);
        CHECK(p99 < 1e-3f);
    }
    MESSAGE(occluded << " pixels occluded below 0.9, " << emitting << " emitting");
    CHECK(occluded > int(full.size()) / 4);
    CHECK(emitting > int(full.size()) / 4);
}
