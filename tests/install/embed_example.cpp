// Renders a built-in scene through the library, a still and a short sequence with a history,
// and prints the mean of the display image (docs/embedding.md, "Embedding the library").
#include <ssrt/renderer/renderer.h>
#include <ssrt/scenes/builtin_scenes.h>

#include <cstdio>

int main() {
    ssrt::RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    const ssrt::Renderer renderer(settings);
    const ssrt::Scene scene = ssrt::makeBuiltinScene("cornell");
    const ssrt::Frame still = renderer.renderWithoutHistory(scene);
    const ssrt::PlaneF& viewZ = still.gbuffer.viewZ;

    ssrt::Frame frame;
    ssrt::FrameHistory history;
    for (uint32_t i = 0; i < 3; ++i) {
        ssrt::FrameInput input = ssrt::FrameInput::still(scene, i);
        renderer.render(scene, input, history, frame);
    }
    const ssrt::PlaneF& red = frame.rgb(ssrt::Res::Display)[0];
    double sum = 0.0;
    for (int y = 0; y < red.height(); ++y)
        for (int x = 0; x < red.width(); ++x) sum += red.at(x, y);
    std::printf("mean display.R = %.4f over %zu planes, frame %u\n",
                sum / (red.width() * red.height()), frame.layers().size(), frame.index);
    return sum > 0.0 && viewZ.width() == 160 && frame.index == 2 ? 0 : 1;
}
