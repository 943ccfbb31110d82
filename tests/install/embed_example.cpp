// Renders a built-in scene through the library and prints the mean of the display image.
#include <ssrt/renderer/renderer.h>
#include <ssrt/scenes/builtin_scenes.h>

#include <cstdio>

int main() {
    ssrt::RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    const ssrt::Renderer renderer(settings);
    const ssrt::Frame frame = renderer.renderWithoutHistory(ssrt::makeBuiltinScene("cornell"));
    const ssrt::PlaneF& red = frame.image.display[0];
    double sum = 0.0;
    for (int y = 0; y < red.height(); ++y)
        for (int x = 0; x < red.width(); ++x) sum += red.at(x, y);
    std::printf("mean display.R = %.4f over %zu planes\n", sum / (red.width() * red.height()),
                frame.layers().size());
    return sum > 0.0 ? 0 : 1;
}
