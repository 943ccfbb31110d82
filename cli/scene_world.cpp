#include "cli/scene_world.h"

namespace ssrt::cli {

SceneWorld::SceneWorld(const Scene& scene, const TraceSettings& trace) {
    if (!trace.worldRays()) return;
    embree_ = std::make_unique<EmbreeScene>(scene);
    rays_ = std::make_unique<EmbreeWorldRays>(*embree_);
}

}  // namespace ssrt::cli
