// A shot's render settings applied through the settings' field table
// (renderer/settings_fields.h): the layer that knows both the shot (scenes/shot.h) and the
// renderer. The shot parser keeps each "render" key as the JSON wrote it; this checks every key
// against the table (unknown keys, types and ranges) as pbrt-v4 reports unused parameters.
#pragma once

#include <string>
#include <vector>

#include "renderer/settings.h"
#include "scenes/shot.h"

namespace ssrt {

// Applies the shot's render fields to `settings` (and its frame index), then validates them.
// Throws ShotError, one line naming the file and the key ("shot.json: render.width: expected
// an integer from 1 to 8192"), for an unknown key, a wrong type or a value out of range.
void applyShot(const Shot& shot, RenderSettings& settings);

// The keys a shot's "render" object takes, in order: every shot field of the table, then
// frames and frame.
std::string shotRenderKeys();
std::vector<std::string> shotRenderKeyList();  // the same, one key each

}  // namespace ssrt
