// What the commands' --json prints, and the pieces of it the Python module (python/) returns as
// dicts too, so that a fact has one name whichever way a script reads it: the CLI dumps these
// documents to stdout, the module converts the same documents to dicts (python/json_dict.h).
// The schemas are documented with each command (docs/cli.md, docs/golden.md, docs/truth.md).
#pragma once

#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "io/image_compare.h"
#include "renderer/frame.h"
#include "truth/evaluation.h"
#include "truth/image_error.h"

namespace ssrt::cli {

// Keys keep the order they were added in, the order the text output prints its rows.
using Json = nlohmann::ordered_json;

// Writes `document` to `out`, indented, with a final line break. A number that is not finite
// (a diff's max error against a NaN) is written as null: JSON has no infinity.
void printJson(std::ostream& out, const Json& document);

// A text table's row label as a JSON key: lower case, '%' as "percent", every run of other
// characters one '_' ("triangles set up": triangles_set_up; "hidden, no ray": hidden_no_ray;
// "lanes active %": lanes_active_percent). The text and JSON outputs name a row from one label.
std::string jsonKey(std::string_view label);

// One image error: {rel_mse, rmse, non_finite} (`ssrt compare`, ssrt.compare()).
Json imageErrorJson(const ImageError& error);
// The colour's error, then its parts' when measured: {color, direct, specular, diffuse}.
Json errorTableJson(const ErrorTable& table);

// One layer of a diff against its thresholds (`ssrt diff`, ssrt.diff()): {channels, present,
// identical, passed, why, max_error, max_at: [x, y, channel], rel_mse, non_finite, pixels_over,
// share_over}; a layer missing from a file has present false and zeros.
Json layerDiffJson(const LayerDiff& layer, const DiffThresholds& limits);
// A whole diff: {width, height, identical (every layer bit for bit), passed (every layer within
// the limits), layers: {name: layerDiffJson}} in the table's order.
Json imageDiffJson(const ImageDiff& diff, const DiffThresholds& limits);

// The built-in scenes: {name: description} in their order (`ssrt scenes`, ssrt.builtin_scenes()).
Json builtinScenesJson();

}  // namespace ssrt::cli
