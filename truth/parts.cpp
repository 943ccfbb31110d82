#include "truth/parts.h"

#include <stdexcept>
#include <string>

#include "core/plane_view.h"
#include "shading/composite.h"

namespace ssrt {

namespace {

// 1 where the pixel shows a surface: the reference's SSR replaces the sky's specular there.
PlaneF surfaceOpacity(const Frame& frame) {
    const PlaneF& viewZ = frame.gbuffer.viewZ;
    PlaneF o(frame.width, frame.height);
    for (int y = 0; y < frame.height; ++y)
        for (int x = 0; x < frame.width; ++x) o.at(x, y) = viewZ.at(x, y) > 0.0f ? 1.0f : 0.0f;
    return o;
}

}  // namespace

void specularDiffuse(const Frame& frame, const FloatPlane ssr[3], const PlaneF& opacity,
                     const FloatPlane ssgi[3], PlaneF specular[3], PlaneF diffuse[3]) {
    const DirectParts& parts = frame.direct;
    const PlaneF& viewZ = frame.gbuffer.viewZ;
    const PlaneF& metallic = frame.gbuffer.metallic;
    // The occlusion texture's share of the SSGI term (envDiffuse has it already).
    const PlaneF* occlusion = frame.gbuffer.occlusion.empty() ? nullptr : &frame.gbuffer.occlusion;
    for (int c = 0; c < 3; ++c) {
        specular[c].ensureSize(frame.width, frame.height);
        diffuse[c].ensureSize(frame.width, frame.height);
        const PlaneF& albedo = frame.gbuffer.albedo[c];
        for (int y = 0; y < frame.height; ++y)
            for (int x = 0; x < frame.width; ++x) {
                // The composite's operations, in its order.
                const float o = opacity.at(x, y);
                const float incoming =
                    ssr[c].at(x, y) * o + decodeF16(parts.envSpecular[c].at(x, y)) * (1.0f - o);
                specular[c].at(x, y) = decodeF16(parts.specWeight[c].at(x, y)) * incoming;
                const float colour = albedo.at(x, y) * (1.0f - metallic.at(x, y));
                float bounce = colour * ssgi[c].at(x, y);
                if (occlusion) bounce *= occlusion->at(x, y);
                diffuse[c].at(x, y) = viewZ.at(x, y) <= 0.0f ? 0.0f : bounce;
            }
    }
}

FrameParts frameParts(const Frame& frame) {
    const DirectParts& parts = frame.direct;
    if (parts.direct[0].width() != frame.width || parts.direct[0].height() != frame.height)
        throw std::invalid_argument(
            "frame parts: the frame has no direct parts (both trace "
            "passes were off)");
    FrameParts fp;
    // A pass that was off stands in as the composite has it: SSR off is opacity 0 (the sky's
    // specular alone), SSGI off is the sky's diffuse light.
    // Where the denoiser ran, the composite read its planes: the specular one as the whole
    // incoming radiance (opacity 1 over it), the diffuse one in place of SSGI's (whose own
    // planes may then not be made: RenderSettings::debugPlanes).
    const std::span<const PlaneF, 3> denoisedSpecular = frame.rgb(Res::DenoisedSpecular);
    const std::span<const PlaneF, 3> denoisedDiffuse = frame.rgb(Res::DenoisedDiffuse);
    const bool specDenoised = !denoisedSpecular[0].empty();
    const bool diffDenoised = !denoisedDiffuse[0].empty();
    const bool ssrOn = !frame.plane(Res::SsrOpacity).empty();
    const bool ssgiOn = !frame.plane(Res::SsgiHit).empty() || diffDenoised;
    const PlaneF opacity = !ssrOn         ? PlaneF(frame.width, frame.height)
                           : specDenoised ? PlaneF(frame.width, frame.height, 1.0f)
                                          : PlaneF();
    FloatPlane ssr[3];
    FloatPlane ssgi[3];
    for (int c = 0; c < 3; ++c) {
        ssr[c] = !ssrOn         ? FloatPlane(&parts.envSpecular[c])
                 : specDenoised ? FloatPlane(&denoisedSpecular[c])
                                : FloatPlane(&frame.rgb(Res::Ssr)[c]);
        ssgi[c] = !ssgiOn        ? FloatPlane(&parts.envDiffuse[c])
                  : diffDenoised ? FloatPlane(&denoisedDiffuse[c])
                                 : FloatPlane(&frame.rgb(Res::Ssgi)[c]);
    }
    specularDiffuse(frame, ssr, ssrOn && !specDenoised ? frame.plane(Res::SsrOpacity) : opacity,
                    ssgi, fp.specular, fp.diffuse);
    for (int c = 0; c < 3; ++c) {
        fp.direct[c] = decodedF16(parts.direct[c]);
        if (!ssgiOn) fp.diffuse[c] = decodedF16(parts.envDiffuse[c]);
    }
    return fp;
}

void composeReference(Isa isa, const Frame& frame, float exposure, bool anyEmissive, int threads,
                      ReferenceImage& ref) {
    const DirectParts& parts = frame.direct;
    const PlaneF opacity = surfaceOpacity(frame);
    const int w = ref.direct[0].width(), h = ref.direct[0].height();
    CompositeArgs ca;
    PlaneF display[3];
    for (int c = 0; c < 3; ++c) {
        ca.direct[c] = viewOf(ref.direct[c], "direct");
        if (anyEmissive) ca.emission[c] = viewOf(parts.emission[c], "emission");
        ca.envDiffuse[c] = viewOf(parts.envDiffuse[c], "envDiffuse");
        ca.envSpecular[c] = viewOf(parts.envSpecular[c], "envSpecular");
        ca.specWeight[c] = viewOf(parts.specWeight[c], "specWeight");
        ca.ssgi[c] = viewOf(ref.ssgi[c], "ssgi");
        ca.ssrColor[c] = viewOf(ref.ssr[c], "ssr");
        ref.color[c].ensureSize(w, h);
        display[c] = PlaneF(w, h);
        ca.color[c] = outputOf(ref.color[c], "color");
        ca.display[c] = outputOf(display[c], "display");
    }
    ca.g = frame.gbuffer.view();
    if (!frame.gbuffer.occlusion.empty())
        ca.occlusion = viewOf(frame.gbuffer.occlusion, "occlusion");
    ca.ssrOpacity = viewOf(opacity, "ssrOpacity");
    ca.exposure = exposure;
    composite(isa, ca, threads);
    const FloatPlane ssr[3] = {&ref.ssr[0], &ref.ssr[1], &ref.ssr[2]};
    const FloatPlane ssgi[3] = {&ref.ssgi[0], &ref.ssgi[1], &ref.ssgi[2]};
    specularDiffuse(frame, ssr, opacity, ssgi, ref.specular, ref.diffuse);
}

}  // namespace ssrt
