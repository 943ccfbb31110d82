// Files and judgements: ssrt.write (a frame to EXR or PNG, as `ssrt render -o`), ssrt.read_layers
// (an image file's channels), ssrt.diff (two files against thresholds, as `ssrt diff`) and
// ssrt.compare (a frame against the Embree truth, as `ssrt compare`'s image error).
#include <pybind11/stl.h>

#include <filesystem>

#include "binding.h"
#include "cli/json_output.h"
#include "io/image_compare.h"
#include "io/image_io.h"
#include "json_dict.h"
#include "renderer/layer_groups.h"
#include "scenes/gltf_loader.h"
#include "scenes/shot.h"
#include "truth/evaluation.h"
#include "truth/reference_image.h"
#include "world/embree_scene.h"

namespace ssrt::python {

void withFiles(const std::vector<std::string>& paths, const std::function<void()>& fn) {
    try {
        fn();
    } catch (const py::error_already_set&) {
        throw;
    } catch (const py::builtin_exception&) {
        throw;
    } catch (const std::invalid_argument& e) {
        throw py::value_error(e.what());
    } catch (const std::exception& e) {
        for (const std::string& p : paths) {
            std::error_code ec;
            if (!p.empty() && !std::filesystem::exists(p, ec)) {
                PyErr_SetString(PyExc_FileNotFoundError, e.what());
                throw py::error_already_set();
            }
        }
        if (dynamic_cast<const SceneLoadError*>(&e) || dynamic_cast<const ShotError*>(&e))
            throw py::value_error(e.what());
        throw std::runtime_error(e.what());  // pybind11: RuntimeError
    }
}

py::array planeView(const PlaneF& plane, py::handle owner) {
    const auto h = py::ssize_t(plane.height()), w = py::ssize_t(plane.width());
    const auto rowBytes = py::ssize_t(plane.stride() * sizeof(float));
    py::array view(py::dtype::of<float>(), {h, w}, {rowBytes, py::ssize_t(sizeof(float))},
                   plane.row(0), owner);
    // pybind11 marks a view of a base object writeable; the renderer's planes are not the
    // caller's to change.
    py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return view;
}

std::string pathText(py::handle value, const char* what) {
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    const py::module_ os = py::module_::import("os");
    if (py::isinstance(value, os.attr("PathLike")))
        return py::str(os.attr("fspath")(value)).cast<std::string>();
    throw py::type_error(std::string(what) + ": expected a str or an os.PathLike, got " +
                         py::repr(value.get_type()).cast<std::string>());
}

namespace {

LayerGroups layerGroupsOf(const std::vector<std::string>& names) {
    LayerGroups groups;
    for (const std::string& n : names) {
        if (n == "all") {
            groups = allLayerGroups();
            continue;
        }
        const std::optional<LayerGroup> g = parseLayerGroup(n);
        if (!g)
            throw py::value_error("layers: invalid value '" + n + "' (expected all or one of " +
                                  layerGroupList() + ")");
        groups.set(int(*g));
    }
    return groups;
}

void writeFrame(const PyFrame& frame, py::handle pathObject, const std::vector<std::string>& layers,
                const std::string& compression, int threads) {
    const std::string path = pathText(pathObject, "write: path");
    WriteOptions options;
    const std::optional<ExrCompression> c = parseExrCompression(compression);
    if (!c)
        throw py::value_error("compression: invalid value '" + compression + "' (expected one of " +
                              exrCompressionList() + ")");
    options.compression = *c;
    options.threads = threads;
    if (threads < 0) throw py::value_error("threads: expected an integer >= 0 (0: every core)");
    const LayerGroups groups = isExrPath(path) ? layerGroupsOf(layers) : allLayerGroups();
    // A missing folder is FileNotFoundError, as open() has it; the file itself may be new.
    const std::string folder = std::filesystem::path(path).parent_path().string();
    withFiles({folder.empty() ? "." : folder}, [&] {
        py::gil_scoped_release unlocked;
        writeImage(path, frameLayers(*frame.frame, groups), options);
    });
}

// Every channel of an image file as a float32 array of its own (a copy: the file's, not a view).
py::dict readLayers(py::handle pathObject) {
    const std::string path = pathText(pathObject, "read_layers: path");
    std::vector<std::string> names;
    std::vector<std::vector<float>> channels;
    int width = 0, height = 0;
    withFiles({path}, [&] {
        py::gil_scoped_release unlocked;
        names = readChannelNames(path);
        channels = readChannels(path, names, width, height);
    });
    py::dict out;
    for (std::size_t i = 0; i < names.size(); ++i) {
        py::array_t<float> a({py::ssize_t(height), py::ssize_t(width)});
        std::copy(channels[i].begin(), channels[i].end(), a.mutable_data());
        out[py::str(names[i])] = a;
    }
    return out;
}

// `ssrt diff A REFERENCE` as a dict: identical, passed, and per layer what compareImages finds,
// the keys of `ssrt diff --json` (cli/json_output.h imageDiffJson).
py::dict diffFiles(py::handle a, py::handle b, double threshold, std::optional<double> maxError,
                   std::optional<double> maxRelMse, double maxShare,
                   const std::vector<std::string>& layers, std::optional<std::string> heatmap) {
    const std::string pa = pathText(a, "diff: a"), pb = pathText(b, "diff: reference");
    if (!(threshold >= 0.0)) throw py::value_error("threshold: expected a number >= 0");
    if (!(maxShare >= 0.0 && maxShare <= 1.0))
        throw py::value_error("max_share: expected a number in [0, 1]");
    ImageCompareOptions options;  // (the heat map's layer and scale: their defaults)
    options.threshold = threshold;
    options.layers = layers;
    options.heatmap = heatmap.value_or("");
    const DiffThresholds limits{maxError, maxRelMse, maxShare};
    ImageDiff diff;
    withFiles({pa, pb}, [&] {
        py::gil_scoped_release unlocked;
        diff = compareImages(pa, pb, options);
    });
    return jsonToPython(cli::imageDiffJson(diff, limits));
}

// The frame against the Embree reference of its lighting model (truth/reference_image.h):
// image error of the exposed colour and of its parts, and the reference's planes.
py::dict compareFrame(const PyFrame& frame, int spp, int bounces, const std::string& visibility) {
    ReferenceSettings rs;
    rs.spp = spp;
    rs.bounces = bounces;
    if (visibility == "embree") rs.visibility = ReferenceSettings::Visibility::Embree;
    else if (visibility == "shadowmap") rs.visibility = ReferenceSettings::Visibility::ShadowMap;
    else
        throw py::value_error("visibility: invalid value '" + visibility +
                              "' (expected embree or shadowmap)");
    auto reference = std::make_shared<ReferenceImage>();
    ErrorTable error;
    withFiles({}, [&] {
        rs.validate();
        if (!frame.settings.trace.ssr || !frame.settings.trace.ssgi)
            throw std::invalid_argument(
                "compare: the frame must be rendered with ssr and ssgi on (the reference reads "
                "both passes' parts)");
        py::gil_scoped_release unlocked;
        const EmbreeScene embree(frame.scene->scene);
        const Renderer renderer(frame.settings);
        *reference = renderReference(embree, renderer, *frame.frame, rs);
        error = imageErrors(*frame.frame, *reference);
    });
    // The image errors under `ssrt compare --json`'s image_error keys.
    py::dict out = jsonToPython(cli::errorTableJson(error));
    // The reference's planes as views owned by a capsule holding it.
    const py::capsule owner(new std::shared_ptr<ReferenceImage>(reference), [](void* p) {
        delete static_cast<std::shared_ptr<ReferenceImage>*>(p);
    });
    py::dict planes;
    const char* suffix[3] = {".R", ".G", ".B"};
    for (int c = 0; c < 3; ++c) {
        planes[py::str(std::string("ref.color") + suffix[c])] =
            planeView(reference->color[c], owner);
        planes[py::str(std::string("ref.ssr") + suffix[c])] = planeView(reference->ssr[c], owner);
        planes[py::str(std::string("ref.ssgi") + suffix[c])] = planeView(reference->ssgi[c], owner);
    }
    out["reference"] = planes;
    return out;
}

}  // namespace

void bindFiles(py::module_& m) {
    m.def("write", &writeFrame, py::arg("frame"), py::arg("path"), py::kw_only(),
          py::arg("layers") = std::vector<std::string>{"all"}, py::arg("compression") = "rle",
          py::arg("threads") = 0,
          "Writes the frame as `ssrt render -o PATH` does: .exr (every plane of the layer groups "
          "given, float, lossless `compression`) or .png (the display planes), whole or not at "
          "all.");
    m.def("read_layers", &readLayers, py::arg("path"),
          "Every channel of an image file (EXR, PNG, ...): name -> float32 array (a copy).");
    m.def("diff", &diffFiles, py::arg("a"), py::arg("reference"), py::kw_only(),
          py::arg("threshold") = 0.0, py::arg("max_error") = py::none(),
          py::arg("max_rel_mse") = py::none(), py::arg("max_share") = 0.0,
          py::arg("layers") = std::vector<std::string>{}, py::arg("heatmap") = py::none(),
          "Two image files compared layer by layer as `ssrt diff A REFERENCE` does, with the "
          "keys of `ssrt diff --json`: {'width', 'height', 'identical', 'passed', 'layers': "
          "{name: {...}}}. A pixel differs when a channel "
          "differs by more than `threshold`; a layer passes within max_error, max_rel_mse and "
          "max_share (the share of pixels that differ).");
    m.def("compare", &compareFrame, py::arg("frame"), py::kw_only(), py::arg("spp") = 64,
          py::arg("bounces") = ReferenceSettings::kConverged, py::arg("visibility") = "embree",
          "The frame against the Embree truth, as `ssrt compare` measures its image: the "
          "reference of the frame's lighting model (spp rays per pixel for SSR and SSGI; its "
          "SSGI paths `bounces` diffuse hits long, 1 to 256, or 0: all the light, until a "
          "path's throughput is below 0.1 %, as compare's default), the relMSE and RMSE of the "
          "colour and its parts, and the reference's planes. The GIL is released while Embree "
          "works.");
}

}  // namespace ssrt::python
