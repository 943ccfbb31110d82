// The world rays a command hands the renderer (FrameInput::world) when a signal is traced in
// mixed or world mode: Embree's scene of the command's scene, built once, and nothing when
// every signal stays on screen.
#pragma once

#include <memory>

#include "renderer/settings.h"
#include "scenes/scene.h"
#include "world/embree_world_rays.h"

namespace ssrt::cli {

class SceneWorld {
public:
    // Keeps a reference to `scene`, which must outlive this.
    SceneWorld(const Scene& scene, const TraceSettings& trace);
    const WorldRays* rays() const { return rays_.get(); }

private:
    std::unique_ptr<EmbreeScene> embree_;
    std::unique_ptr<EmbreeWorldRays> rays_;
};

}  // namespace ssrt::cli
