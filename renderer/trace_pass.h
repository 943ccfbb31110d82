// The screen-space passes of a frame, after the G-buffer and the direct light: Hi-Z, then
// per sample ray generation, march and resolve for SSR and SSGI, then the composite that
// replaces the direct pass's color and display planes.
#pragma once

#include "renderer/renderer.h"
#include "shading/direct_kernel.h"

namespace ssrt {

// Names of the planes the trace passes add to a frame, in frame order.
std::vector<const char*> tracePlaneNames(const TraceSettings& settings);

// `direct` is the direct pass's argument block (sky, light, shadow map), as it ran; its
// parts outputs pointed into frame.scratch.directParts. Appends pass times and stats to
// frame.stats.
// `observer` (optional) sees each sample's rays and march result.
void runTracePasses(const RenderSettings& settings, Isa isa, const TraceCamera& camera,
                    const DirectArgs& direct, Frame& frame, const TraceObserver* observer);

}  // namespace ssrt
