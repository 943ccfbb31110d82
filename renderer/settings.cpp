#include "renderer/settings.h"

#include <stdexcept>

#include "renderer/settings_fields.h"

namespace ssrt {

// Each field in its range, as the tables (renderer/settings_fields.h) give it; the nested
// structs check their own.
void RenderSettings::validate() const {
    checkFields(kRenderOwnFields, *this, "RenderSettings");
    trace.validate();
}

void TraceSettings::validate() const {
    checkFields(kTraceOwnFields, *this, "TraceSettings");
    // (The table lets ssrLayout take full and checkerboard only; a struct set in code may
    // still hold half, which has no SSR march at half resolution.)
    if (ssrLayout == TraceLayout::Half)
        throw std::invalid_argument(
            "TraceSettings.ssrLayout: expected one of full, checkerboard (half is SSGI's only)");
    march.validate();
    checkFields(kResolveFields, resolve, "SsrResolveSettings");
    denoise.validate();
}

}  // namespace ssrt
