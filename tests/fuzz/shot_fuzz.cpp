// libFuzzer target for shot files (scenes/shot.h): every input either gives a shot whose
// render settings, camera, light, environment and camera path apply to a scene, or is refused
// with ShotError; anything else (a crash, a sanitizer report, another exception) is a bug.
#include <cstdint>
#include <string_view>

#include "cli/shot_settings.h"
#include "fuzz_files.h"
#include "scenes/builtin_scenes.h"
#include "scenes/shot.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // The built-in scene's camera and sky, without its meshes (applyShot reads neither).
    static const ssrt::Scene base = [] {
        ssrt::Scene scene = ssrt::makeBuiltinScene("spheres");
        scene.meshes.clear();
        scene.instances.clear();
        scene.materials.clear();
        return scene;
    }();
    // From text (loadShot is this after reading the file); paths resolve against the
    // harness's folder.
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const ssrt::Shot shot = ssrt::parseShot(text, ssrt::fuzz::workDir() + "/shot.json");
        ssrt::RenderSettings settings;
        ssrt::applyShot(shot, settings);
        ssrt::Scene scene = base;
        ssrt::applyShot(shot, scene);
        ssrt::shotCameraPath(shot, scene.camera);
    } catch (const ssrt::ShotError&) {
        // refused cleanly: fine
    }
    return 0;
}
