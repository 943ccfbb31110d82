// The CLI's --json documents (cli/json_output.h) as Python objects, so that a function here
// returns the dict `ssrt COMMAND --json` prints, key for key: an object is a dict (in its
// order), an array a tuple (a diff's max_at was one before the documents were shared), null
// None. A number keeps its value: an infinity the CLI prints as null is float('inf') here.
#pragma once

#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

namespace ssrt::python {

inline pybind11::object jsonToPython(const nlohmann::ordered_json& j) {
    namespace py = pybind11;
    switch (j.type()) {
        case nlohmann::json::value_t::null: return py::none();
        case nlohmann::json::value_t::boolean: return py::bool_(j.get<bool>());
        case nlohmann::json::value_t::number_integer: return py::int_(j.get<int64_t>());
        case nlohmann::json::value_t::number_unsigned: return py::int_(j.get<uint64_t>());
        case nlohmann::json::value_t::number_float: return py::float_(j.get<double>());
        case nlohmann::json::value_t::string: return py::str(j.get<std::string>());
        case nlohmann::json::value_t::array: {
            py::tuple out(j.size());
            for (std::size_t i = 0; i < j.size(); ++i) out[i] = jsonToPython(j[i]);
            return out;
        }
        case nlohmann::json::value_t::object: {
            py::dict out;
            for (const auto& [key, value] : j.items()) out[py::str(key)] = jsonToPython(value);
            return out;
        }
        default: return py::none();  // (binary and discarded values: never in a document)
    }
}

}  // namespace ssrt::python
