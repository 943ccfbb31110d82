// The reference image for a request, from the cache when it holds one, else rendered (with
// progress) and stored. Files are EXRs named by referenceKey() (truth/
// reference_image.h), so any change to the scene or to a setting that shapes the reference
// makes a new file; nothing is ever read back for a different request.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>

#include "renderer/renderer.h"
#include "truth/embree_scene.h"
#include "truth/reference_image.h"

namespace ssrt::cli {

// $SSRT_CACHE_DIR, else $XDG_CACHE_HOME/ssrt, else $HOME/.cache/ssrt (empty if none is set).
std::string defaultCacheDir();

struct ReferenceSource {
    std::optional<std::string> cacheDir;  // nullopt: no cache (always render, store nothing)
    std::ostream* progress = nullptr;     // "reference: 42%" lines; null: quiet
};

// The reference for `settings` (its trace settings' SSR sampler and frame index; both trace
// passes are turned on for the frame it is rendered over). `fromCache` tells where it came
// from. A cache file that cannot be read or does not match is rendered again and replaced.
ReferenceImage referenceFor(const EmbreeScene& embree, const Scene& scene, const FrameInput& input,
                            const RenderSettings& settings, const ReferenceSettings& reference,
                            const ReferenceSource& source, bool& fromCache);

}  // namespace ssrt::cli
