// Scenes and what changes per frame: ssrt.Scene (a built-in name or a glTF file), ssrt.Shot
// (a shot file: scene, settings, camera path, frames), ssrt.Camera and ssrt.FrameInput. They
// are loaded exactly as `ssrt render` loads them (cli/options.h loadSceneRequest and
// loadScene), so the same names, files and mistakes give the same scenes and messages.
#include <pybind11/stl.h>

#include <sstream>

#include "binding.h"
#include "cli/json_output.h"
#include "cli/sequence.h"
#include "json_dict.h"
#include "scenes/builtin_scenes.h"

namespace ssrt::python {

namespace {

using Vec3 = std::array<float, 3>;

Vec3 toArray(const glm::vec3& v) { return {v.x, v.y, v.z}; }

// A glTF file's warnings, each as a Python warning (the CLI prints them on stderr).
void warnEach(const std::string& lines) {
    std::istringstream in(lines);
    std::string line;
    while (std::getline(in, line))
        if (!line.empty()) PyErr_WarnEx(PyExc_UserWarning, line.c_str(), 1);
}

// Loads what `options` names (a scene, or a shot with its scene) as the CLI does.
struct Loaded {
    SceneData scene;
    cli::SequencePlan plan;
};
Loaded load(const cli::RenderOptions& options, const std::string& path) {
    auto request = std::make_shared<cli::SceneRequest>();
    cli::SequencePlan plan;
    std::ostringstream warnings;
    withFiles({path}, [&] {
        py::gil_scoped_release unlocked;
        *request = cli::loadSceneRequest(options);
        plan = cli::sequencePlanFrom(options, *request);
        cli::loadScene(*request, warnings);
    });
    warnEach(warnings.str());
    return {request, plan};
}

PyScene loadScene(py::handle name, bool strict) {
    cli::RenderOptions options;
    options.scene = pathText(name, "Scene: name");
    options.strict = strict;
    return {load(options, *options.scene).scene};
}

struct PyShot {
    PyScene scene;
    RenderSettings settings;
    cli::SequencePlan plan;
    uint32_t firstFrame = 0;
};

PyShot loadShot(py::handle path, bool strict) {
    cli::RenderOptions options;
    options.shot = pathText(path, "Shot: path");
    options.strict = strict;
    Loaded loaded = load(options, *options.shot);
    const RenderSettings settings = loaded.scene->settings;
    const uint32_t first = loaded.scene->firstFrame;
    return {{loaded.scene}, settings, loaded.plan, first};
}

void bindCamera(py::module_& m) {
    py::class_<Camera>(m, "Camera", "A camera: position, target, up, vertical field of view.")
        .def_property_readonly("position", [](const Camera& c) { return toArray(c.position); })
        .def_property_readonly("target", [](const Camera& c) { return toArray(c.target); })
        .def_property_readonly("up", [](const Camera& c) { return toArray(c.up); })
        .def_readonly("fov_y", &Camera::fovY, "Vertical field of view, degrees")
        .def_readonly("near", &Camera::nearZ)
        .def_readonly("far", &Camera::farZ);
}

void bindFrameInput(py::module_& m) {
    py::class_<FrameInput>(m, "FrameInput",
                           "What changes from one frame of a sequence to the next: the frame "
                           "index (it seeds the random numbers), the camera and the previous "
                           "one (motion vectors), a cut.")
        .def_static(
            "still",
            [](const PyScene& s, uint32_t index) {
                return FrameInput::still(s.data->scene, index);
            },
            py::arg("scene"), py::arg("frame_index") = 0,
            "The scene's own camera and previous camera at this frame index.")
        .def_readwrite("frame_index", &FrameInput::frameIndex)
        .def_readonly("camera", &FrameInput::camera)
        .def_readonly("previous_camera", &FrameInput::previousCamera)
        .def_readwrite("reset_history", &FrameInput::resetHistory,
                       "A cut: the history is not read (and is replaced)")
        .def_readwrite("replace_history", &FrameInput::replaceHistory,
                       "False: the history is read but left as it was (the last frame)");
}

}  // namespace

void bindScenes(py::module_& m) {
    bindCamera(m);
    py::class_<PyScene>(m, "Scene",
                        "A scene as `ssrt render --scene` loads it: a built-in name (see "
                        "ssrt.builtin_scenes()) or a .gltf/.glb file. strict: every warning about "
                        "the file is an error.")
        .def(py::init(&loadScene), py::arg("name"), py::kw_only(), py::arg("strict") = false)
        .def_property_readonly("name", [](const PyScene& s) { return s.data->name; })
        .def_property_readonly("camera", [](const PyScene& s) { return s.data->scene.camera; })
        .def_property_readonly("triangles",
                               [](const PyScene& s) { return s.data->scene.triangleCount(); })
        .def("__repr__", [](const PyScene& s) { return "ssrt.Scene('" + s.data->name + "')"; });

    bindFrameInput(m);  // after Scene, so that its signatures name the class
    py::class_<PyShot>(m, "Shot",
                       "A shot file as `ssrt render --shot` reads it: its scene (with its camera "
                       "path, light and sky), its settings over the defaults, and its frames.")
        .def(py::init(&loadShot), py::arg("path"), py::kw_only(), py::arg("strict") = false)
        .def_readonly("scene", &PyShot::scene)
        .def_readonly("settings", &PyShot::settings)
        .def_property_readonly("frames", [](const PyShot& s) { return s.plan.frames; })
        .def_property_readonly("warmup_frames", [](const PyShot& s) { return s.plan.warmup; })
        .def_readonly("first_frame", &PyShot::firstFrame);

    m.def(
        "builtin_scenes", [] { return py::dict(jsonToPython(cli::builtinScenesJson())); },
        "The built-in scenes: name -> one line on what each shows (`ssrt scenes --json`).");
}

}  // namespace ssrt::python
