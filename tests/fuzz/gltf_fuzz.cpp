// libFuzzer target for the glTF loader: every input either loads into a valid scene or is
// refused with SceneLoadError; anything else (a crash, a sanitizer report, another
// exception, a hang) is a bug. Inputs are written to a file because the loader reads paths
// (external buffers resolve beside it).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scenes/gltf_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string dir = "/tmp/ssrt-gltf-fuzz-" + std::to_string(::getpid());
    static const bool made = (std::system(("mkdir -p " + dir).c_str()) == 0);
    if (!made) return 0;
    // Alternate the extension on the first byte so both parsers (JSON and GLB) are fuzzed.
    const std::string path = dir + (size > 0 && (data[0] & 1) ? "/in.glb" : "/in.gltf");
    if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    } else {
        return 0;
    }
    try {
        const ssrt::Scene scene = ssrt::loadGltf(path);
        scene.validate();  // a loaded scene must be valid
    } catch (const ssrt::SceneLoadError&) {
        // refused cleanly: fine
    }
    return 0;
}
