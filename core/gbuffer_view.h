// The G-buffer's planes, listed once (GBufferOf), and the G-buffer as passes and kernels read
// it (GBufferView: each plane's first row, the one stride the planes share and their size).
//
// GBufferOf<P> holds one P per plane: an owned plane where the planes live (renderer/frame.h's
// GBuffer, the half frame's in trace/trace_layout.h, the denoiser's history guides), a read-only
// row where a pass reads them (GBufferView), a writable row where a kernel writes them (the
// rasterizer's resolve). A holder that keeps only some planes leaves the rest empty, and names
// and sizes only those (forEach's mask). Plain data where P is: views cross into code compiled
// per ISA.
//
// A view is made in one place, gbufferView, which checks every plane it is given (of the
// size asked, so one stride serves them all); a pass then states the planes it reads with
// requireGBuffer. Both throw std::invalid_argument naming the pass and the plane.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string_view>

#include "core/image.h"

namespace ssrt {

// The planes, one bit each (a set: GBufferPlanes), in GBufferOf's order.
enum GBufferPlane : uint32_t {
    kGViewZ = 1u << 0,
    kGNormalX = 1u << 1,
    kGNormalY = 1u << 2,
    kGNormalZ = 1u << 3,
    kGAlbedoR = 1u << 4,
    kGAlbedoG = 1u << 5,
    kGAlbedoB = 1u << 6,
    kGMetallic = 1u << 7,
    kGRoughness = 1u << 8,
    kGMaterialId = 1u << 9,
    kGMotionX = 1u << 10,
    kGMotionY = 1u << 11,
    kGEmissionR = 1u << 12,
    kGEmissionG = 1u << 13,
    kGEmissionB = 1u << 14,
    kGOcclusion = 1u << 15,
    kGInstanceId = 1u << 16,
    kGTriangleId = 1u << 17,
};
using GBufferPlanes = uint32_t;
inline constexpr int kGBufferPlaneCount = 18;
inline constexpr GBufferPlanes kGNormal = kGNormalX | kGNormalY | kGNormalZ;
inline constexpr GBufferPlanes kGAlbedo = kGAlbedoR | kGAlbedoG | kGAlbedoB;
inline constexpr GBufferPlanes kGMotion = kGMotionX | kGMotionY;
inline constexpr GBufferPlanes kGEmission = kGEmissionR | kGEmissionG | kGEmissionB;
inline constexpr GBufferPlanes kGAllPlanes = (1u << kGBufferPlaneCount) - 1u;

// The G-buffer: attributes of the visible surface per pixel. Background pixels: viewZ 0,
// materialId -1, motion 0, instance and triangle -1, the rest 0.
template <class P>
struct GBufferOf {
    P viewZ{};        // positive view-space depth
    P normal[3]{};    // world space, unit
    P albedo[3]{};    // base colour (linear)
    P metallic{};     //
    P roughness{};    // perceptual
    P materialId{};   // the scene's material index
    P motion[2]{};    // previous minus current position, pixels
    P emission[3]{};  // scene-linear radiance (with emissive textures)
    P occlusion{};    // 1 where a material has no occlusion texture (with occlusion textures)
    P instanceId{};   // as floats (RenderSettings::idPlanes)
    P triangleId{};

    // Calls fn(which, plane) for each plane in `mask`, in GBufferPlane's order: the one list of
    // the G-buffer's planes that every holder walks. G: a GBufferOf<P> (or derived), const or not.
    template <class G, class Fn>
    static void forEach(G& g, Fn&& fn, GBufferPlanes mask = kGAllPlanes) {
        const auto one = [&](GBufferPlane which, auto& p) {
            if (mask & which) fn(which, p);
        };
        const auto three = [&](GBufferPlane first, auto& p) {
            for (int i = 0; i < 3; ++i) one(GBufferPlane(first << i), p[i]);
        };
        one(kGViewZ, g.viewZ);
        three(kGNormalX, g.normal);
        three(kGAlbedoR, g.albedo);
        one(kGMetallic, g.metallic);
        one(kGRoughness, g.roughness);
        one(kGMaterialId, g.materialId);
        one(kGMotionX, g.motion[0]);
        one(kGMotionY, g.motion[1]);
        three(kGEmissionR, g.emission);
        one(kGOcclusion, g.occlusion);
        one(kGInstanceId, g.instanceId);
        one(kGTriangleId, g.triangleId);
    }
    // The plane `which` (one bit).
    template <class G>
    static auto& at(G& g, GBufferPlane which) {
        decltype(&g.viewZ) found = nullptr;
        forEach(g, [&](GBufferPlane w, auto& p) {
            if (w == which) found = &p;
        });
        return *found;
    }
};

// Owned planes (empty: not held).
using GBufferPlanesF = GBufferOf<PlaneF>;

struct GBufferView : GBufferOf<const float*> {
    std::size_t stride = 0;
    int width = 0, height = 0;
};

// One plane given to gbufferView: which it is, and the plane (null: absent).
struct GBufferSlot {
    GBufferPlane which;
    const PlaneF* plane;
};

// The view of `planes`, each of width x height (an empty or null plane is left out), every
// plane in `need` present; else std::invalid_argument naming `pass` and the plane.
GBufferView gbufferView(std::string_view pass, int width, int height, const GBufferSlot* planes,
                        std::size_t count, GBufferPlanes need = 0);
inline GBufferView gbufferView(std::string_view pass, int width, int height,
                               std::initializer_list<GBufferSlot> planes, GBufferPlanes need = 0) {
    return gbufferView(pass, width, height, planes.begin(), planes.size(), need);
}
// The view of the planes an owner holds (its empty ones absent), as above.
GBufferView gbufferView(std::string_view pass, int width, int height, const GBufferPlanesF& planes,
                        GBufferPlanes need = 0);

// `to` with the planes of `from` in `mask` (absent ones absent); both of one size and stride,
// else std::invalid_argument.
GBufferView withPlanes(GBufferView to, const GBufferView& from, GBufferPlanes mask);

// A pass's check of the view it was handed: of width x height, with every plane in `need`;
// else std::invalid_argument naming `pass` and the plane.
void requireGBuffer(std::string_view pass, const GBufferView& g, GBufferPlanes need, int width,
                    int height);

// The plane's name ("viewZ", "normal.X", ...): its channel's name in the frame's resource table
// (renderer/resources.cpp; tests/renderer/frame_test.cpp holds the two to each other).
std::string_view gbufferPlaneName(GBufferPlane which);
// The name after a prefix ("half.gbuffer." + "normal.X"): a holder's channel names, spelt here
// once and kept for the program's life (a table's names outlive its walks).
std::string_view gbufferPlaneName(std::string_view prefix, GBufferPlane which);

// Calls fn(name, plane) for each plane of `g` in `mask`, named prefix + gbufferPlaneName: a
// PlaneTable's table() over the G-buffer planes it holds.
template <class G, class Fn>
void forEachGBufferChannel(std::string_view prefix, G& g, GBufferPlanes mask, Fn& fn) {
    GBufferPlanesF::forEach(
        g, [&](GBufferPlane which, auto& p) { fn(gbufferPlaneName(prefix, which), p); }, mask);
}

}  // namespace ssrt
