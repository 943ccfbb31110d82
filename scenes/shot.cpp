#include "scenes/shot.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/suggest.h"
#include "scenes/scene_names.h"

namespace ssrt {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::string join(std::initializer_list<const char*> names) {
    std::string out;
    for (const char* n : names) out += (out.empty() ? "" : ", ") + std::string(n);
    return out;
}

std::string formatNumber(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// Finite, and finite as a float too (checked before converting: a double beyond the float
// range has no float value).
bool fitsFloat(double v) {
    return std::isfinite(v) && std::fabs(v) <= double(std::numeric_limits<float>::max());
}

// Reads one document, every error naming the file and the JSON path of the field.
class Reader {
public:
    Reader(std::string file) : file_(std::move(file)) {}

    [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
        throw ShotError(file_ + ": " + (path.empty() ? "" : path + ": ") + problem);
    }

    static std::string child(const std::string& path, const std::string& key) {
        return path.empty() ? key : path + "." + key;
    }

    // `j` must be an object whose keys are all in `allowed`.
    void object(const json& j, const std::string& path,
                std::initializer_list<const char*> allowed) const {
        if (!j.is_object())
            fail(path,
                 path.empty() ? "expected a JSON object at the top level" : "expected an object");
        for (const auto& item : j.items()) {
            const bool known = std::any_of(allowed.begin(), allowed.end(),
                                           [&](const char* a) { return item.key() == a; });
            if (!known)
                fail(child(path, item.key()),
                     "unknown key" +
                         didYouMean(item.key(),
                                    std::vector<std::string>(allowed.begin(), allowed.end())) +
                         " (expected one of: " + join(allowed) + ")");
        }
    }

    // A finite number in the range given by lo/hi and whether each end is included.
    std::optional<double> number(const json& obj, const std::string& path, const char* key,
                                 double lo, bool loIn, double hi, bool hiIn,
                                 const std::string& expected) const {
        if (!obj.contains(key)) return std::nullopt;
        const json& j = obj[key];
        const std::string p = child(path, key);
        if (!j.is_number()) fail(p, "expected " + expected);
        const double v = j.get<double>();
        // Finite also as a float: every number here ends up in one.
        const bool inRange = fitsFloat(v) && (loIn ? v >= lo : v > lo) && (hiIn ? v <= hi : v < hi);
        if (!inRange) fail(p, "expected " + expected);
        return v;
    }

    std::optional<float> positive(const json& obj, const std::string& path, const char* key) const {
        const auto v = number(obj, path, key, 0.0, false, kFloatMax, true, "a finite number > 0");
        return v ? std::optional<float>(float(*v)) : std::nullopt;
    }
    std::optional<float> nonNegative(const json& obj, const std::string& path,
                                     const char* key) const {
        const auto v = number(obj, path, key, 0.0, true, kFloatMax, true, "a finite number >= 0");
        return v ? std::optional<float>(float(*v)) : std::nullopt;
    }

    // An integer written as one (1280, not 1280.0 or 1.28e3) in [lo, hi].
    std::optional<long long> integer(const json& obj, const std::string& path, const char* key,
                                     long long lo, long long hi) const {
        if (!obj.contains(key)) return std::nullopt;
        const json& j = obj[key];
        const std::string p = child(path, key);
        const std::string expected =
            "an integer from " + std::to_string(lo) + " to " + std::to_string(hi);
        if (!j.is_number_integer()) fail(p, "expected " + expected);
        if (j.is_number_unsigned()) {
            const auto u = j.get<unsigned long long>();
            // (nlohmann-json reads every non-negative integer as unsigned)
            if (u > static_cast<unsigned long long>(hi) ||
                (lo > 0 && u < static_cast<unsigned long long>(lo)))
                fail(p, "expected " + expected);
            return static_cast<long long>(u);
        }
        const auto v = j.get<long long>();
        if (v < lo || v > hi) fail(p, "expected " + expected);
        return v;
    }

    enum class VecRule { Any, NonZero, NonNegative };

    std::optional<glm::vec3> vec3(const json& obj, const std::string& path, const char* key,
                                  VecRule rule) const {
        if (!obj.contains(key)) return std::nullopt;
        const json& j = obj[key];
        const std::string p = child(path, key);
        const std::string expected =
            rule == VecRule::NonNegative ? "an array of 3 finite numbers >= 0"
            : rule == VecRule::NonZero   ? "an array of 3 finite numbers, not all 0"
                                         : "an array of 3 finite numbers";
        if (!j.is_array() || j.size() != 3) fail(p, "expected " + expected);
        glm::vec3 v;
        for (int i = 0; i < 3; ++i) {
            if (!j[i].is_number()) fail(p, "expected " + expected);
            const double d = j[i].get<double>();
            if (!fitsFloat(d)) fail(p, "expected " + expected);
            if (rule == VecRule::NonNegative && d < 0.0) fail(p, "expected " + expected);
            v[i] = float(d);
        }
        // Zero-length also after rounding to float (1e-50 becomes 0).
        if (rule == VecRule::NonZero && v == glm::vec3(0.0f)) fail(p, "expected " + expected);
        return v;
    }

    std::optional<std::string> string(const json& obj, const std::string& path,
                                      const char* key) const {
        if (!obj.contains(key)) return std::nullopt;
        const json& j = obj[key];
        if (!j.is_string() || j.get<std::string>().empty())
            fail(child(path, key), "expected a non-empty string");
        return j.get<std::string>();
    }

    // A path relative to the shot file's folder (absolute paths stay); it must exist.
    std::string existingFile(const std::string& path, const std::string& value) const {
        fs::path p(value);
        if (p.is_relative()) p = fs::path(file_).parent_path() / p;
        std::error_code ec;
        if (!fs::is_regular_file(p, ec)) fail(path, "no such file '" + p.string() + "'");
        return p.string();
    }

    static constexpr double kFloatMax = std::numeric_limits<float>::max();

private:
    std::string file_;
};

// Parses with a callback that tracks the JSON path, to report the first duplicate key
// (nlohmann-json keeps the last value silently).
json parseDocument(const std::string& text, const Reader& r) {
    struct Level {
        bool array = false;
        std::string key;
        long index = -1;
        std::set<std::string> keys;
    };
    std::vector<Level> stack;
    std::optional<std::string> duplicate;
    const auto pathOf = [&] {
        std::string p;
        for (const Level& l : stack) {
            // Built with append: GCC 12 gives a false -Wrestrict for "." + std::string.
            if (l.array) {
                p.append("[").append(std::to_string(l.index)).append("]");
            } else if (!l.key.empty()) {
                if (!p.empty()) p.append(".");
                p.append(l.key);
            }
        }
        return p;
    };
    const auto elementStarts = [&] {
        if (!stack.empty() && stack.back().array) ++stack.back().index;
    };
    const json::parser_callback_t callback = [&](int, json::parse_event_t event, json& parsed) {
        switch (event) {
            case json::parse_event_t::object_start:
            case json::parse_event_t::array_start:
                elementStarts();
                stack.push_back({event == json::parse_event_t::array_start, {}, -1, {}});
                break;
            case json::parse_event_t::object_end:
            case json::parse_event_t::array_end:
                if (!stack.empty()) stack.pop_back();
                break;
            case json::parse_event_t::key:
                if (!stack.empty()) {
                    stack.back().key = parsed.get<std::string>();
                    if (!stack.back().keys.insert(stack.back().key).second && !duplicate)
                        duplicate = pathOf();
                }
                break;
            case json::parse_event_t::value: elementStarts(); break;
        }
        return true;
    };
    json doc;
    try {
        doc = json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/false);
    } catch (const json::out_of_range&) {
        // A number beyond double (1e999): the path is where the parser stopped, the element
        // being read when inside an array.
        elementStarts();
        r.fail(pathOf(), "expected a finite number (it overflows)");
    } catch (const json::exception& e) {
        // "[json.exception.parse_error.101] parse error at line 3, column 7: ..." -> from "line"
        std::string what = e.what();
        const std::size_t at = what.find("at line ");
        if (at != std::string::npos) what = what.substr(at + 3);
        else if (const std::size_t b = what.find("] "); b != std::string::npos)
            what = what.substr(b + 2);
        r.fail("", "not valid JSON: " + what);
    }
    if (duplicate) r.fail(*duplicate, "duplicate key");
    return doc;
}

}  // namespace

Shot parseShot(const std::string& text, const std::string& file) {
    using VR = Reader::VecRule;
    const Reader r(file);
    const json doc = parseDocument(text, r);
    r.object(doc, "", {"scene", "camera", "light", "environment", "render"});
    Shot shot;
    shot.file = file;

    // scene
    if (const auto scene = r.string(doc, "", "scene")) {
        if (isSceneFile(*scene)) {
            shot.scene = r.existingFile("scene", *scene);
        } else {
            if (!isBuiltinScene(*scene))
                r.fail("scene", "unknown scene '" + *scene + "'" +
                                    didYouMean(*scene, knownSceneNames()) +
                                    " (known: " + knownScenes() + "; or a .gltf/.glb file)");
            shot.scene = *scene;
        }
    }

    // camera
    if (doc.contains("camera")) {
        const json& cam = doc["camera"];
        const std::string p = "camera";
        r.object(cam, p, {"position", "target", "up", "fovY", "near", "far", "path"});
        auto& c = shot.camera;
        c.position = r.vec3(cam, p, "position", VR::Any);
        c.target = r.vec3(cam, p, "target", VR::Any);
        c.up = r.vec3(cam, p, "up", VR::NonZero);
        if (const auto v =
                r.number(cam, p, "fovY", 0.0, false, 180.0, false, "a number in (0, 180)"))
            c.fovY = float(*v);
        c.nearZ = r.positive(cam, p, "near");
        c.farZ = r.positive(cam, p, "far");
        if (c.nearZ && c.farZ && !(*c.farZ > *c.nearZ))
            r.fail("camera.far",
                   "expected a number greater than near (" + formatNumber(*c.nearZ) + ")");
        if (cam.contains("path")) {
            const json& path = cam["path"];
            const std::string pp = "camera.path";
            r.object(path, pp, {"interpolation", "keys"});
            if (const auto interp = r.string(path, pp, "interpolation")) {
                if (*interp == "catmull-rom") shot.interpolation = PathInterpolation::CatmullRom;
                else if (*interp == "linear") shot.interpolation = PathInterpolation::Linear;
                else r.fail(pp + ".interpolation", "expected \"catmull-rom\" or \"linear\"");
            }
            if (!path.contains("keys") || !path["keys"].is_array() || path["keys"].empty())
                r.fail(pp + ".keys", "expected an array of at least one key");
            const json& keys = path["keys"];
            for (std::size_t k = 0; k < keys.size(); ++k) {
                const std::string kp = pp + ".keys[" + std::to_string(k) + "]";
                r.object(keys[k], kp, {"time", "position", "target", "fovY", "cut"});
                ShotKey key;
                key.time = r.number(keys[k], kp, "time", -Reader::kFloatMax, true,
                                    Reader::kFloatMax, true, "a finite number");
                if (!key.time) key.time = double(k);
                if (k > 0 && !(*key.time > *shot.path.back().time))
                    r.fail(kp + ".time", "expected a time greater than the previous key's (" +
                                             formatNumber(*shot.path.back().time) + ")");
                key.position = r.vec3(keys[k], kp, "position", VR::Any);
                key.target = r.vec3(keys[k], kp, "target", VR::Any);
                if (const auto v = r.number(keys[k], kp, "fovY", 0.0, false, 180.0, false,
                                            "a number in (0, 180)"))
                    key.fovY = float(*v);
                if (keys[k].contains("cut")) {
                    if (!keys[k]["cut"].is_boolean()) r.fail(kp + ".cut", "expected true or false");
                    key.cut = keys[k]["cut"].get<bool>();
                    if (k == 0 && key.cut)
                        r.fail(kp + ".cut",
                               "the first key cannot be a cut (nothing comes before "
                               "it to cut from)");
                }
                shot.path.push_back(key);
            }
        }
    }

    // light
    if (doc.contains("light")) {
        const json& light = doc["light"];
        r.object(light, "light", {"direction", "color", "intensity"});
        shot.light.direction = r.vec3(light, "light", "direction", VR::NonZero);
        shot.light.color = r.vec3(light, "light", "color", VR::NonNegative);
        shot.light.intensity = r.nonNegative(light, "light", "intensity");
    }

    // environment: the type decides which keys may follow
    if (doc.contains("environment")) {
        const json& e = doc["environment"];
        const std::string p = "environment";
        if (!e.is_object()) r.fail(p, "expected an object");
        auto& env = shot.environment;
        std::optional<std::string> type;
        if (e.contains("type")) {
            type = r.string(e, p, "type");
            if (*type != "constant" && *type != "gradient" && *type != "image")
                r.fail(p + ".type", "expected \"constant\", \"gradient\" or \"image\"");
        }
        if (!type) {
            r.object(e, p, {"type", "intensity"});
        } else if (*type == "constant") {
            r.object(e, p, {"type", "color", "intensity"});
            env.kind = Sky::Kind::Constant;
            env.color = r.vec3(e, p, "color", VR::NonNegative);
        } else if (*type == "gradient") {
            r.object(e, p, {"type", "zenith", "horizon", "ground", "intensity"});
            env.kind = Sky::Kind::Gradient;
            env.zenith = r.vec3(e, p, "zenith", VR::NonNegative);
            env.horizon = r.vec3(e, p, "horizon", VR::NonNegative);
            env.ground = r.vec3(e, p, "ground", VR::NonNegative);
        } else {
            r.object(e, p, {"type", "file", "intensity"});
            env.kind = Sky::Kind::Image;
            const auto f = r.string(e, p, "file");
            if (!f) r.fail(p + ".file", "required when type is \"image\"");
            env.file = r.existingFile(p + ".file", *f);
        }
        env.intensity = r.nonNegative(e, p, "intensity");
    }

    // render: frames and frame here, every other key a setting for the caller's table
    if (doc.contains("render")) {
        const json& rd = doc["render"];
        const std::string p = "render";
        if (!rd.is_object()) r.fail(p, "expected an object");
        auto& s = shot.render;
        if (const auto f = r.integer(rd, p, "frames", 1, kMaxShotFrames)) s.frames = int(*f);
        if (const auto f = r.integer(rd, p, "frame", 0, 4294967295ll)) s.frame = uint32_t(*f);
        if (const auto f = r.integer(rd, p, "warmupFrames", 0, kMaxShotFrames))
            s.warmupFrames = int(*f);
        for (const auto& item : rd.items()) {
            if (item.key() == "frames" || item.key() == "frame" || item.key() == "warmupFrames")
                continue;
            const json& j = item.value();
            ShotValue v;
            if (j.is_boolean()) {
                v.kind = ShotValue::Kind::Bool;
                v.number = j.get<bool>() ? 1.0 : 0.0;
            } else if (j.is_number_integer()) {
                v.kind = ShotValue::Kind::Integer;
                v.number = j.is_number_unsigned() ? double(j.get<unsigned long long>())
                                                  : double(j.get<long long>());
            } else if (j.is_number()) {
                v.kind = ShotValue::Kind::Number;
                v.number = j.get<double>();
            } else if (j.is_string()) {
                v.kind = ShotValue::Kind::String;
                v.text = j.get<std::string>();
            }
            s.settings.emplace_back(item.key(), std::move(v));
        }
    }
    return shot;
}

Shot loadShot(const std::string& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw ShotError(path + ": is a directory, not a shot file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ShotError(path + ": cannot read the shot file (" + std::strerror(errno) + ")");
    std::ostringstream text;
    text << in.rdbuf();
    return parseShot(text.str(), path);
}

namespace {

// The camera must be able to look somewhere: position off the target, up off the view axis.
void checkCamera(const Camera& c, const std::string& file, const std::string& path) {
    const glm::vec3 view = c.target - c.position;
    if (view == glm::vec3(0.0f))
        throw ShotError(file + ": " + path + ": position and target are the same point");
    const glm::vec3 side = glm::cross(view, c.up);
    if (side == glm::vec3(0.0f))
        throw ShotError(file + ": " + path + ": up is parallel to the view direction");
}

}  // namespace

void applyShot(const Shot& shot, Scene& scene) {
    Camera& c = scene.camera;
    const auto& sc = shot.camera;
    if (sc.position) c.position = *sc.position;
    if (sc.target) c.target = *sc.target;
    if (sc.up) c.up = *sc.up;
    if (sc.fovY) c.fovY = *sc.fovY;
    if (sc.nearZ) c.nearZ = *sc.nearZ;
    if (sc.farZ) c.farZ = *sc.farZ;
    if (!(c.farZ > c.nearZ))
        throw ShotError(shot.file + ": camera: far (" + formatNumber(c.farZ) +
                        ") must be greater than near (" + formatNumber(c.nearZ) + ")");
    checkCamera(c, shot.file, "camera");
    scene.previousCamera = c;

    DirectionalLight& l = scene.light;
    if (shot.light.direction) l.direction = glm::normalize(*shot.light.direction);
    if (shot.light.color) l.color = *shot.light.color;
    if (shot.light.intensity) l.intensity = *shot.light.intensity;

    Sky& sky = scene.sky;
    const auto& e = shot.environment;
    if (e.kind) sky.kind = *e.kind;
    if (e.color) sky.zenith = sky.horizon = sky.ground = *e.color;
    if (e.zenith) sky.zenith = *e.zenith;
    if (e.horizon) sky.horizon = *e.horizon;
    if (e.ground) sky.ground = *e.ground;
    if (e.intensity) sky.intensity = *e.intensity;
    if (sky.kind != Sky::Kind::Image) sky.image.reset();
}

CameraPath shotCameraPath(const Shot& shot, const Camera& camera) {
    CameraPath path;
    path.interpolation = shot.interpolation;
    for (std::size_t k = 0; k < shot.path.size(); ++k) {
        const ShotKey& sk = shot.path[k];
        CameraKey key;
        key.time = sk.time.value_or(double(k));
        key.position = sk.position.value_or(camera.position);
        key.target = sk.target.value_or(camera.target);
        key.fovY = sk.fovY.value_or(camera.fovY);
        key.cut = sk.cut;
        Camera c = camera;
        c.position = key.position;
        c.target = key.target;
        checkCamera(c, shot.file, "camera.path.keys[" + std::to_string(k) + "]");
        path.keys.push_back(key);
    }
    try {
        path.validate();
    } catch (const std::invalid_argument& e) {
        throw ShotError(shot.file + ": camera.path: " + e.what());
    }
    return path;
}

}  // namespace ssrt
