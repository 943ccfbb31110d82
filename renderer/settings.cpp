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
    march.validate();
    checkFields(kResolveFields, resolve, "SsrResolveSettings");
    denoise.validate();
}

}  // namespace ssrt
