// ssrt.RenderSettings: every field of the settings' table (renderer/settings_fields.h) as a
// keyword argument and an attribute, named as the table names it in snake case
// (shadowMapSize: shadow_map_size), checked against the table's range with the messages the
// CLI gives, and described by the table's help in the class's docstring. Nothing here lists
// a setting: a field added to the table appears in Python, its stubs and help().
#include <pybind11/stl.h>

#include <cctype>
#include <sstream>

#include "binding.h"
#include "core/suggest.h"
#include "renderer/quality.h"
#include "renderer/settings_fields.h"

namespace ssrt::python {

namespace {

using RenderField = Field<RenderSettings>;

std::string snakeCase(std::string_view key) {
    std::string out;
    for (char c : key) {
        if (std::isupper(static_cast<unsigned char>(c))) out.append("_").push_back(char(c + 32));
        else out.push_back(c);
    }
    return out;
}

const char* pythonType(const FieldInfo& f) {
    switch (f.type) {
        case FieldType::Bool: return "bool";
        case FieldType::Int: return "int";
        case FieldType::Float: return "float";
        case FieldType::Choice: return "str";
    }
    return "object";
}

// The value as Python shows it: True, 1280, 0.1, 'hiz'.
py::object pythonValue(const FieldInfo& f, double v) {
    switch (f.type) {
        case FieldType::Bool: return py::bool_(v != 0.0);
        case FieldType::Int: return py::int_(static_cast<long long>(v));
        case FieldType::Float: return py::float_(v);
        case FieldType::Choice: return py::str(f.text(v));
    }
    return py::none();
}

[[noreturn]] void badValue(const std::string& name, py::handle value, const std::string& expected,
                           bool wrongType) {
    const std::string message = name + ": invalid value " + py::repr(value).cast<std::string>() +
                                " (expected " + expected + ")";
    if (wrongType) throw py::type_error(message);
    throw py::value_error(message);
}

// The number a Python value gives the field, checked as the CLI checks its text.
double fieldValue(const FieldInfo& f, const std::string& name, py::handle value) {
    const bool isBool = py::isinstance<py::bool_>(value);
    switch (f.type) {
        case FieldType::Bool:
            if (!isBool) badValue(name, value, "True or False", true);
            return value.cast<bool>() ? 1.0 : 0.0;
        case FieldType::Int: {
            if (isBool || !py::isinstance<py::int_>(value))
                badValue(name, value, f.expected(), true);
            // Beyond 64 bits is out of every range: refuse it before the cast overflows.
            const py::int_ big(1ll << 53);
            if (value > big || value < -big) badValue(name, value, f.expected(), false);
            const double v = double(value.cast<long long>());
            if (!f.accepts(v)) badValue(name, value, f.expected(), false);
            return v;
        }
        case FieldType::Float: {
            if (isBool || !(py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)))
                badValue(name, value, f.expected(), true);
            const double v = double(value.cast<float>());
            if (!f.accepts(v) || !f.accepts(value.cast<double>()))
                badValue(name, value, f.expected(), false);
            return v;
        }
        case FieldType::Choice: {
            if (!py::isinstance<py::str>(value))
                badValue(name, value, "one of " + f.choiceList(), true);
            const int i = f.choiceIndex(value.cast<std::string>());
            if (i < 0) badValue(name, value, "one of " + f.choiceList(), false);
            return i;
        }
    }
    return 0.0;
}

const RenderField* findField(const std::string& name) {
    for (const RenderField& f : kRenderFields)
        if (snakeCase(f.key) == name) return &f;
    return nullptr;
}

std::vector<std::string> keywords() {
    std::vector<std::string> out = {"quality", "isa"};
    for (const RenderField& f : kRenderFields) out.push_back(snakeCase(f.key));
    return out;
}

std::string keywordList() {
    std::string out;
    for (const std::string& k : keywords()) out += (out.empty() ? "" : ", ") + k;
    return out;
}

void setIsa(RenderSettings& s, py::handle value) {
    if (!py::isinstance<py::str>(value))
        badValue("isa", value, "auto, scalar, sse2, sse42, avx2 or avx512", true);
    try {
        s.isa = parseIsa(value.cast<std::string>());
    } catch (const std::exception& e) {
        throw py::value_error(std::string("isa: ") + e.what());
    }
}

// quality first (a preset the other keywords then override, as --quality and the flags beside
// it), then every other keyword, then the checks across fields (RenderSettings::validate).
RenderSettings settingsFrom(RenderSettings s, const py::kwargs& kwargs) {
    if (kwargs.contains("quality")) {
        const py::handle q = kwargs["quality"];
        const std::optional<Quality> preset =
            py::isinstance<py::str>(q) ? parseQuality(q.cast<std::string>()) : std::nullopt;
        if (!preset)
            badValue("quality", q, "one of " + std::string(qualityList()),
                     !py::isinstance<py::str>(q));
        applyQuality(*preset, s);
    }
    for (const auto& [key, value] : kwargs) {
        const std::string name = key.cast<std::string>();
        if (name == "quality") continue;
        if (name == "isa") {
            setIsa(s, value);
            continue;
        }
        const RenderField* f = findField(name);
        if (!f)
            throw py::type_error("RenderSettings: unknown keyword '" + name + "'" +
                                 didYouMean(name, keywords()) + " (known: " + keywordList() + ")");
        f->set(s, fieldValue(*f, name, value));
    }
    try {
        s.validate();
    } catch (const std::invalid_argument& e) {
        throw py::value_error(e.what());
    }
    return s;
}

// help(ssrt.RenderSettings): each keyword with its type, default, range and the table's help.
std::string classDoc() {
    const RenderSettings d;
    std::ostringstream doc;
    doc << "RenderSettings(**keywords): the renderer's settings, immutable once a Renderer holds "
           "them.\n\nKeywords (each also an attribute; replace() gives a changed copy):\n"
        << "  quality: str -- a preset applied first, one of " << qualityList()
        << " (the defaults are " << qualityName(kDefaultQuality) << "'s)\n"
        << "  isa: str = 'auto' -- kernels to run: auto ($SSRT_ISA if set, else the best this "
           "CPU runs), scalar, sse2, sse42, avx2 or avx512\n";
    for (const RenderField& f : kRenderFields)
        doc << "  " << snakeCase(f.key) << ": " << pythonType(f) << " = "
            << py::repr(pythonValue(f, f.get(d))).cast<std::string>() << " -- " << f.help << " ("
            << f.expected() << ")\n";
    return doc.str();
}

// RenderSettings.fields(): the table for tools (the stub generator, docs).
py::list fieldList() {
    const RenderSettings d;
    py::list out;
    for (const RenderField& f : kRenderFields) {
        py::dict e;
        e["name"] = snakeCase(f.key);
        e["key"] = std::string(f.key);
        e["type"] = pythonType(f);
        e["default"] = pythonValue(f, f.get(d));
        e["expected"] = f.expected();
        e["help"] = std::string(f.help);
        py::list choices;
        for (int i = 0; i < f.choiceCount; ++i) choices.append(std::string(f.choiceName(i)));
        e["choices"] = choices;
        out.append(e);
    }
    return out;
}

std::string settingsRepr(const RenderSettings& s) {
    const RenderSettings d;
    std::string out = "RenderSettings(";
    bool first = true;
    for (const RenderField& f : kRenderFields) {
        if (f.get(s) == f.get(d)) continue;
        out += (first ? "" : ", ") + snakeCase(f.key) + "=" +
               py::repr(pythonValue(f, f.get(s))).cast<std::string>();
        first = false;
    }
    if (s.isa)
        out += (first ? "" : ", ") + std::string("isa='") + std::string(isaName(*s.isa)) + "'";
    return out + ")";
}

}  // namespace

void bindSettings(py::module_& m) {
    py::class_<RenderSettings> cls(m, "RenderSettings", classDoc().c_str());
    cls.def(py::init([](const py::kwargs& kw) { return settingsFrom(RenderSettings{}, kw); }))
        .def(
            "replace",
            [](const RenderSettings& s, const py::kwargs& kw) { return settingsFrom(s, kw); },
            "A copy with the keywords given changed (the same keywords as the constructor).")
        .def_static("fields", &fieldList,
                    "Every field of the settings' table: name, key, type, default, expected, "
                    "help, choices.")
        .def("__repr__", &settingsRepr)
        .def("__eq__", [](const RenderSettings& a, const RenderSettings& b) {
            for (const RenderField& f : kRenderFields)
                if (f.get(a) != f.get(b)) return false;
            return a.isa == b.isa;
        });
    for (const RenderField& field : kRenderFields) {
        const RenderField* f = &field;  // the tables are constexpr statics: pointers stay valid
        const std::string name = snakeCase(f->key);
        cls.def_property(
            name.c_str(), [f](const RenderSettings& s) { return pythonValue(*f, f->get(s)); },
            [f, name](RenderSettings& s, py::handle v) { f->set(s, fieldValue(*f, name, v)); },
            (std::string(f->help) + " (" + f->expected() + ")").c_str());
    }
    cls.def_property(
        "isa",
        [](const RenderSettings& s) { return std::string(s.isa ? isaName(*s.isa) : "auto"); },
        [](RenderSettings& s, py::handle v) { setIsa(s, v); },
        "Kernels to run: auto, scalar, sse2, sse42, avx2 or avx512");
}

}  // namespace ssrt::python
