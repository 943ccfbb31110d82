#include "core/gbuffer_view.h"

#include <span>
#include <stdexcept>
#include <string>

#include "core/plane_view.h"

namespace ssrt {

namespace {

// The view's member for plane `which` (GBufferView's order); V: GBufferView, const or not.
template <class V>
auto& member(V& g, GBufferPlane which) {
    switch (which) {
        case kGViewZ: return g.viewZ;
        case kGNormalX: return g.normal[0];
        case kGNormalY: return g.normal[1];
        case kGNormalZ: return g.normal[2];
        case kGAlbedoR: return g.albedo[0];
        case kGAlbedoG: return g.albedo[1];
        case kGAlbedoB: return g.albedo[2];
        case kGMetallic: return g.metallic;
        case kGRoughness: return g.roughness;
        case kGMaterialId: return g.materialId;
        case kGMotionX: return g.motion[0];
        case kGMotionY: return g.motion[1];
    }
    throw std::logic_error("GBufferView: not a plane");
}

}  // namespace

std::string_view gbufferPlaneName(GBufferPlane which) {
    switch (which) {
        case kGViewZ: return "viewZ";
        case kGNormalX: return "normal.X";
        case kGNormalY: return "normal.Y";
        case kGNormalZ: return "normal.Z";
        case kGAlbedoR: return "albedo.R";
        case kGAlbedoG: return "albedo.G";
        case kGAlbedoB: return "albedo.B";
        case kGMetallic: return "metallic";
        case kGRoughness: return "roughness";
        case kGMaterialId: return "materialId";
        case kGMotionX: return "motion.X";
        case kGMotionY: return "motion.Y";
    }
    return "?";
}

unsigned gbufferPlaneNamed(std::string_view name) {
    for (int i = 0; i < kGBufferPlaneCount; ++i)
        if (gbufferPlaneName(GBufferPlane(1u << i)) == name) return 1u << i;
    return 0;
}

GBufferView gbufferView(std::string_view pass, int width, int height, const GBufferSlot* planes,
                        std::size_t count, GBufferPlanes need) {
    GBufferView g;
    g.width = width;
    g.height = height;
    for (const GBufferSlot& s : std::span(planes, count)) {
        if (!s.plane || s.plane->empty()) continue;
        const ViewF v = viewOf(*s.plane, gbufferPlaneName(s.which));
        g.stride = requireViews(pass, width, height, {v});
        member(g, s.which) = v.data;
    }
    requireGBuffer(pass, g, need, width, height);
    return g;
}

void requireGBuffer(std::string_view pass, const GBufferView& g, GBufferPlanes need, int width,
                    int height) {
    const std::string who = std::string(pass) + ": the G-buffer";
    if (g.width != width || g.height != height)
        throw std::invalid_argument(who + " is " + std::to_string(g.width) + "x" +
                                    std::to_string(g.height) + ", not " + std::to_string(width) +
                                    "x" + std::to_string(height));
    for (int i = 0; i < kGBufferPlaneCount; ++i) {
        const auto which = GBufferPlane(1u << i);
        if ((need & which) && !member(g, which))
            throw std::invalid_argument(std::string(pass) + ": " +
                                        std::string(gbufferPlaneName(which)) + " is missing");
    }
}

}  // namespace ssrt
