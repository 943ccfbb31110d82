// What the binding's files share: the Python-side objects that own C++ ones, and the calls
// that turn C++ errors into Python exceptions carrying the CLI's one-line messages.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "cli/options.h"
#include "cli/scene_world.h"
#include "renderer/renderer.h"

namespace ssrt::python {

namespace py = pybind11;

// A loaded scene as `ssrt render` loads it (cli/options.h): the scene, the shot's camera path
// and first frame. Shared, immutable: frames and sequences keep it alive while they read it.
using SceneData = std::shared_ptr<const cli::SceneRequest>;

// Embree's scene of a loaded scene (FrameInput::world), built by the first render that traces
// a signal in mixed or world mode and kept with the scene for the others.
struct SceneWorldRays {
    std::once_flag built;
    std::unique_ptr<cli::SceneWorld> world;
};

struct PyScene {
    SceneData data;
    std::shared_ptr<SceneWorldRays> world = std::make_shared<SceneWorldRays>();

    // The world rays a render with `trace` needs (built once, thread-safe), or null where it
    // traces every signal on screen.
    const WorldRays* worldRays(const TraceSettings& trace) const {
        if (!trace.worldRays()) return nullptr;
        std::call_once(world->built, [&] {
            world->world = std::make_unique<cli::SceneWorld>(data->scene, trace);
        });
        return world->world->rays();
    }
};

// A rendered frame, shared with every numpy view of its planes (their base object).
struct PyFrame {
    std::shared_ptr<const Frame> frame;
    RenderSettings settings;  // what rendered it (the truth renders its reference with them)
    SceneData scene;
};

// The caller's history (a second render call using it while one is, from another thread, is
// refused by the renderer: FrameHistory::inUse).
struct PyHistory {
    FrameHistory history;
};

// Runs `fn`; a C++ error becomes the Python exception for its kind, its message unchanged:
// std::invalid_argument -> ValueError; any other -> FileNotFoundError when one of `paths`
// does not exist, ValueError for a file that cannot be understood (SceneLoadError, ShotError),
// else RuntimeError.
void withFiles(const std::vector<std::string>& paths, const std::function<void()>& fn);

// A read-only numpy view of `plane` (float32, rows of the plane's stride), kept alive by
// `owner`.
py::array planeView(const PlaneF& plane, py::handle owner);

// Text from a str or an os.PathLike; TypeError naming `what` otherwise.
std::string pathText(py::handle value, const char* what);

// The module's parts, each in its own file.
void bindSettings(py::module_& m);  // settings.cpp
void bindScenes(py::module_& m);    // scenes.cpp
void bindFrames(py::module_& m);    // frames.cpp
void bindFiles(py::module_& m);     // files.cpp: write, read_layers, diff, compare

}  // namespace ssrt::python
