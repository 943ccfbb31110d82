// The extension module ssrt._ssrt, which the package ssrt (python/ssrt/__init__.py) re-exports.
#include "binding.h"

PYBIND11_MODULE(_ssrt, m) {
    m.doc() =
        "ssrt: a deterministic CPU renderer. Scenes and shots in, frames of named float planes "
        "out (read-only numpy views), bit-identical to the `ssrt` command's EXR layers.";
    ssrt::python::bindSettings(m);
    ssrt::python::bindScenes(m);
    ssrt::python::bindFrames(m);
    ssrt::python::bindFiles(m);
}
