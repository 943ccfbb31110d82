// ssrt.Renderer, ssrt.History, ssrt.Frame and the sequence helper. Rendering releases the
// GIL; a frame's planes come out as read-only numpy views of the renderer's own memory, named
// as the EXR layers (Frame::layers()), without a copy.
#include <pybind11/stl.h>

#include "binding.h"
#include "cli/sequence.h"

namespace ssrt::python {

namespace {

// One frame into a new Frame (views of earlier frames stay as they were), the GIL released. A
// history another thread's render is using is refused by the renderer (RuntimeError).
// A renderer tracing in mixed or world mode gets the scene's world rays unless the input names
// its own.
PyFrame renderOne(const Renderer& renderer, const PyScene& scene, const FrameInput& input,
                  PyHistory* history) {
    auto frame = std::make_shared<Frame>();
    withFiles({}, [&] {
        py::gil_scoped_release unlocked;
        FrameInput in = input;
        if (!in.world) in.world = scene.worldRays(renderer.settings().trace);
        if (history) renderer.render(scene.data->scene, in, history->history, *frame);
        else renderer.renderWithoutHistory(scene.data->scene, in, *frame);
    });
    return {frame, renderer.settings(), scene.data};
}

// ssrt.Renderer.sequence(): the frames `ssrt render --frames N --warmup-frames K` writes, one
// per step of the iteration (cli/sequence.h: cameras along the scene's path, indices, cuts).
class Sequence {
public:
    Sequence(std::shared_ptr<const Renderer> renderer, PyScene scene, cli::SequencePlan plan)
        : renderer_(std::move(renderer)), scene_(std::move(scene)), sequence_(*scene_.data, plan) {}

    PyFrame next() {
        const int steps = sequence_.steps();
        while (step_ < steps) {
            FrameInput input = sequence_.input(step_);
            // No frame reads the last one's history, as in `ssrt render`.
            input.replaceHistory = step_ + 1 < steps;
            const bool warmup = sequence_.isWarmup(step_++);
            PyFrame frame = renderOne(*renderer_, scene_, input, &history_);
            if (!warmup) return frame;
        }
        throw py::stop_iteration();
    }
    int size() const { return sequence_.plan().frames; }

private:
    std::shared_ptr<const Renderer> renderer_;
    PyScene scene_;  // keeps the scene and path alive: sequence_ refers to them
    cli::FrameSequence sequence_;
    PyHistory history_;
    int step_ = 0;
};

cli::SequencePlan planOf(int frames, int warmup) {
    if (frames < 1 || frames > kMaxShotFrames)
        throw py::value_error("frames: invalid value " + std::to_string(frames) +
                              " (expected an integer from 1 to " + std::to_string(kMaxShotFrames) +
                              ")");
    if (warmup < 0 || warmup > kMaxShotFrames)
        throw py::value_error("warmup_frames: invalid value " + std::to_string(warmup) +
                              " (expected an integer from 0 to " + std::to_string(kMaxShotFrames) +
                              ")");
    return {frames, warmup};
}

py::dict planeDict(const py::object& self) {
    const PyFrame& f = self.cast<const PyFrame&>();
    py::dict out;
    for (const PlaneRef& p : f.frame->layers())
        out[py::str(std::string(p.name))] = planeView(*p.plane, self);
    return out;
}

py::array planeNamed(const py::object& self, const std::string& name) {
    const PyFrame& f = self.cast<const PyFrame&>();
    for (const PlaneRef& p : f.frame->layers())
        if (p.name == name) return planeView(*p.plane, self);
    throw py::key_error("frame: no plane '" + name + "' (its planes: Frame.layers)");
}

py::dict passTimes(const PyFrame& f) {
    py::dict out;
    for (const PassTime& p : f.frame->stats.passes) out[py::str(p.name)] = p.ms;
    return out;
}

void bindFrame(py::module_& m) {
    py::class_<PyFrame>(m, "Frame",
                        "A rendered frame. Its planes are read-only float32 numpy views of the "
                        "renderer's memory (shape (height, width)), named as the EXR layers: "
                        "frame['viewZ'], frame['color.R'], ...; they keep the frame alive.")
        .def_property_readonly("width", [](const PyFrame& f) { return f.frame->width; })
        .def_property_readonly("height", [](const PyFrame& f) { return f.frame->height; })
        .def_property_readonly(
            "index", [](const PyFrame& f) { return f.frame->index; },
            "The frame index it was rendered with")
        .def_readonly("settings", &PyFrame::settings)
        .def_property_readonly(
            "layers",
            [](const PyFrame& f) {
                std::vector<std::string> names;
                for (const PlaneRef& p : f.frame->layers()) names.emplace_back(p.name);
                return names;
            },
            "The layer names, in the EXR's order")
        .def("planes", &planeDict, "Every plane: layer name -> read-only view")
        .def("__getitem__", &planeNamed, py::arg("name"))
        .def("__contains__",
             [](const PyFrame& f, const std::string& name) { return f.frame->has(name); })
        .def_property_readonly("pass_times", &passTimes, "Milliseconds per pass, in frame order")
        .def("__repr__", [](const PyFrame& f) {
            return "<ssrt.Frame " + std::to_string(f.frame->width) + "x" +
                   std::to_string(f.frame->height) + ", frame " + std::to_string(f.frame->index) +
                   ", " + std::to_string(f.frame->layers().size()) + " planes>";
        });
}

}  // namespace

void bindFrames(py::module_& m) {
    bindFrame(m);
    py::class_<PyHistory>(m, "History",
                          "What a frame leaves the next one of a sequence; the caller owns it "
                          "and hands it to every frame (Renderer.render).")
        .def(py::init<>())
        .def_property_readonly(
            "valid", [](const PyHistory& h) { return h.history.valid; },
            "A frame has committed into it")
        .def_property_readonly(
            "in_use", [](const PyHistory& h) { return h.history.inUse.held(); },
            "A render call is using it now (another one, from another thread, is refused with "
            "a RuntimeError)");

    py::class_<Sequence>(m, "Sequence", "The frames of Renderer.sequence(), rendered one per step.")
        .def("__iter__", [](py::object self) { return self; })
        .def("__next__", &Sequence::next)
        .def("__len__", &Sequence::size);

    using RendererPtr = std::shared_ptr<Renderer>;
    py::class_<Renderer, RendererPtr>(m, "Renderer",
                                      "Built once from settings; renders frames of any scene.")
        .def(py::init([](const RenderSettings& s) {
                 RendererPtr r;
                 withFiles({}, [&] {
                     s.validate();
                     r = std::make_shared<Renderer>(s);
                 });
                 return r;
             }),
             py::arg("settings") = RenderSettings{})
        .def_property_readonly("settings", &Renderer::settings)
        .def(
            "render",
            [](const Renderer& r, const PyScene& scene, std::optional<FrameInput> input,
               PyHistory* history) {
                return renderOne(r, scene, input ? *input : FrameInput::still(scene.data->scene),
                                 history);
            },
            py::arg("scene"), py::arg("input") = py::none(), py::arg("history") = py::none(),
            "One frame (the scene's still camera at frame 0 without an input). With a "
            "history it reads what the frame before committed and commits its own; without, "
            "it neither reads nor leaves one. The GIL is released while it renders.")
        .def(
            "sequence",
            [](RendererPtr r, const PyScene& scene, int frames, int warmup) {
                return Sequence(std::move(r), scene, planOf(frames, warmup));
            },
            py::arg("scene"), py::arg("frames") = 1, py::kw_only(), py::arg("warmup_frames") = 0,
            "The frames `ssrt render --frames N --warmup-frames K` writes, as an iterator: "
            "along the scene's camera path (a Shot's scene) or of its still camera, one "
            "history throughout, restarted at the path's cuts; warm-up frames are rendered, "
            "not yielded.");
}

}  // namespace ssrt::python
