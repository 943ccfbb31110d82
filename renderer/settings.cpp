#include "renderer/settings.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ssrt {

namespace {

void requireRange(bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
}

}  // namespace

void RenderSettings::validate() const {
    requireRange(width >= 1 && width <= kMaxImageSize,
                 "width must be between 1 and " + std::to_string(kMaxImageSize));
    requireRange(height >= 1 && height <= kMaxImageSize,
                 "height must be between 1 and " + std::to_string(kMaxImageSize));
    requireRange(threads >= 0 && threads <= 1024, "threads must be between 0 and 1024");
    requireRange(shadowMapSize >= 16 && shadowMapSize <= kMaxImageSize,
                 "shadow map size must be between 16 and " + std::to_string(kMaxImageSize));
    requireRange(std::isfinite(shadowBias) && shadowBias >= 0.0f, "shadow bias must be >= 0");
    requireRange(std::isfinite(shadowSlopeBias) && shadowSlopeBias >= 0.0f,
                 "shadow slope bias must be >= 0");
    requireRange(pcfRadius >= 0 && pcfRadius <= 8, "PCF radius must be between 0 and 8");
    requireRange(std::isfinite(exposure) && exposure > 0.0f, "exposure must be finite and > 0");
    trace.validate();
}

void TraceSettings::validate() const {
    requireRange(ssrSpp >= 1 && ssrSpp <= kMaxSpp,
                 "SSR samples per pixel must be between 1 and " + std::to_string(kMaxSpp));
    requireRange(ssgiSpp >= 1 && ssgiSpp <= kMaxSpp,
                 "SSGI samples per pixel must be between 1 and " + std::to_string(kMaxSpp));
    march.validate();
    requireRange(std::isfinite(resolve.edgeFadeLength) && resolve.edgeFadeLength > 0.0f &&
                     resolve.edgeFadeLength <= 0.5f,
                 "SSR edge fade length must be in (0, 0.5]");
    requireRange(std::isfinite(resolve.roughnessFadeStart) &&
                     std::isfinite(resolve.roughnessFadeEnd) &&
                     resolve.roughnessFadeStart >= 0.0f && resolve.roughnessFadeEnd <= 1.0f,
                 "SSR roughness fade must lie in [0, 1]");
}

}  // namespace ssrt
