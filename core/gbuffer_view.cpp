#include "core/gbuffer_view.h"

#include <array>
#include <bit>
#include <map>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>

#include "core/plane_view.h"

namespace ssrt {

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
        case kGEmissionR: return "emissive.R";
        case kGEmissionG: return "emissive.G";
        case kGEmissionB: return "emissive.B";
        case kGOcclusion: return "occlusion";
        case kGInstanceId: return "instanceId";
        case kGTriangleId: return "triangleId";
    }
    return "?";
}

std::string_view gbufferPlaneName(std::string_view prefix, GBufferPlane which) {
    if (prefix.empty()) return gbufferPlaneName(which);
    // (A handful of prefixes in a program, each made once: the names live as long as it does.)
    using Names = std::array<std::string, kGBufferPlaneCount>;
    static std::mutex mutex;
    static std::map<std::string, Names, std::less<>> byPrefix;
    const std::lock_guard lock(mutex);
    auto it = byPrefix.find(prefix);
    if (it == byPrefix.end()) {
        Names names;
        for (int i = 0; i < kGBufferPlaneCount; ++i)
            names[std::size_t(i)] =
                std::string(prefix).append(gbufferPlaneName(GBufferPlane(1u << i)));
        it = byPrefix.emplace(std::string(prefix), std::move(names)).first;
    }
    return it->second[std::size_t(std::countr_zero(uint32_t(which)))];
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
        GBufferView::at(g, s.which) = v.data;
    }
    requireGBuffer(pass, g, need, width, height);
    return g;
}

GBufferView gbufferView(std::string_view pass, int width, int height, const GBufferPlanesF& planes,
                        GBufferPlanes need) {
    GBufferSlot slots[kGBufferPlaneCount];
    std::size_t n = 0;
    GBufferPlanesF::forEach(planes, [&](GBufferPlane which, const PlaneF& p) {
        slots[n++] = {which, &p};
    });
    return gbufferView(pass, width, height, slots, n, need);
}

GBufferView withPlanes(GBufferView to, const GBufferView& from, GBufferPlanes mask) {
    if (to.width != from.width || to.height != from.height || to.stride != from.stride)
        throw std::invalid_argument("withPlanes: G-buffer views of different sizes or strides");
    GBufferView::forEach(
        from, [&](GBufferPlane which, const float* p) { GBufferView::at(to, which) = p; }, mask);
    return to;
}

void requireGBuffer(std::string_view pass, const GBufferView& g, GBufferPlanes need, int width,
                    int height) {
    const std::string who = std::string(pass) + ": the G-buffer";
    if (g.width != width || g.height != height)
        throw std::invalid_argument(who + " is " + std::to_string(g.width) + "x" +
                                    std::to_string(g.height) + ", not " + std::to_string(width) +
                                    "x" + std::to_string(height));
    GBufferView::forEach(g, [&](GBufferPlane which, const float* p) {
        if ((need & which) && !p)
            throw std::invalid_argument(std::string(pass) + ": " +
                                        std::string(gbufferPlaneName(which)) + " is missing");
    });
}

}  // namespace ssrt
