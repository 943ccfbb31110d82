// A tool built on every component of the installed package (docs/embedding.md, "Embedding the
// library"): loads a glTF file (ssrt::gltf), renders a short sequence with a history (core),
// writes the last frame as an EXR and reads a layer back (ssrt::io), and measures it against
// the Embree reference (ssrt::truth, on ssrt::world).
// Usage: tool_example SCENE.gltf OUT.exr
#include <ssrt/io/image_io.h>
#include <ssrt/renderer/layer_groups.h>
#include <ssrt/renderer/renderer.h>
#include <ssrt/scenes/gltf_loader.h>
#include <ssrt/truth/image_error.h>
#include <ssrt/truth/reference_image.h>
#include <ssrt/world/embree_scene.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>

namespace {

// Whether the file's channel holds the plane's very bits.
bool sameAsFile(const std::string& path, const char* channel, const ssrt::PlaneF& plane) {
    int width = 0, height = 0;
    const std::vector<float> values = ssrt::readChannel(path, channel, width, height);
    if (width != plane.width() || height != plane.height()) return false;
    for (int y = 0; y < height; ++y)
        if (std::memcmp(plane.row(y), &values[std::size_t(y) * width], width * sizeof(float)))
            return false;
    return true;
}

int run(const char* scenePath, const char* output) {
    const ssrt::Scene scene = ssrt::loadGltf(scenePath);
    ssrt::RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    const ssrt::Renderer renderer(settings);

    // Four frames of the still camera, each reading what the one before committed.
    ssrt::Frame frame;
    ssrt::FrameHistory history;
    for (uint32_t i = 0; i < 4; ++i)
        renderer.render(scene, ssrt::FrameInput::still(scene, i), history, frame);

    ssrt::writeImage(output, ssrt::frameLayers(frame));
    const bool written = sameAsFile(output, "viewZ", frame.gbuffer.viewZ) &&
                         sameAsFile(output, "color.R", frame.rgb(ssrt::Res::Color)[0]);

    const ssrt::EmbreeScene embree(scene);
    ssrt::ReferenceSettings truth;
    truth.spp = 8;
    const ssrt::ReferenceImage reference = ssrt::renderReference(embree, renderer, frame, truth);
    const auto imageRgb = frame.rgb(ssrt::Res::Color);
    const ssrt::PlaneF* image[3] = {&imageRgb[0], &imageRgb[1], &imageRgb[2]};
    const ssrt::PlaneF* ref[3] = {&reference.color[0], &reference.color[1], &reference.color[2]};
    const ssrt::ImageError error = ssrt::imageError(image, ref);
    std::printf("%s: %zu layers written to %s (%s), relMSE against Embree %.4g\n", scenePath,
                frame.layers().size(), output, written ? "read back bit for bit" : "DIFFERENT",
                error.relMse);
    return written && std::isfinite(error.relMse) && error.nonFinite == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: tool_example SCENE.gltf OUT.exr\n");
        return 2;
    }
    try {
        return run(argv[1], argv[2]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tool_example: %s\n", e.what());
        return 1;
    }
}
