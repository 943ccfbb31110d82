// MarchSettings' field table (core/fields.h): the one list of its settings, their ranges and
// help, behind MarchSettings::validate(), the CLI flags, shot-file keys and the cache key.
#pragma once

#include "core/fields.h"
#include "trace/march.h"

namespace ssrt {

inline constexpr int kMaxMarchSteps = 1 << 20;
inline constexpr int kLastHiZLevel = 15;  // kMaxHiZLevels - 1 (march.cpp checks)

inline constexpr unsigned kMarchUse = kFieldCli | kFieldShot;  // none shapes the reference

inline constexpr std::array kMarchFields = {
    field<&MarchSettings::maxSteps>("maxSteps", kMarchUse,
                                    "March steps per ray (Hi-Z: traversal iterations)")
        .ints(1, kMaxMarchSteps),
    field<&MarchSettings::maxDistance>(
        "maxDistance", kMarchUse,
        "Ray length after which a ray ends, in scene bounding-box diagonals; the reference's "
        "rays too")
        .floats(0.0, true),
    field<&MarchSettings::maxDistanceAbsolute>(
        "maxDistanceAbsolute", kMarchUse,
        "Ray length in scene units, replacing --max-distance when > 0")
        .floats(0.0, false),
    field<&MarchSettings::linearStep>(
        "linearStep", kMarchUse,
        "Linear marcher: step length as a fraction of the ray origin's depth")
        .floats(0.0, true),
    field<&MarchSettings::linearStepAbsolute>(
        "linearStepAbsolute", kMarchUse,
        "Linear marcher: step length in scene units, replacing --linear-step when > 0")
        .floats(0.0, false),
    field<&MarchSettings::thickness>(
        "thickness", kMarchUse,
        "Depth a surface is assumed to have behind the depth buffer, as a fraction of its "
        "depth (with --back-faces, only where its back face is unknown)")
        .floats(0.0, true),
    field<&MarchSettings::thicknessAbsolute>(
        "thicknessAbsolute", kMarchUse,
        "Surface thickness in scene units (view depth), replacing --thickness when > 0")
        .floats(0.0, false),
    field<&MarchSettings::backFaces>(
        "backFaces", kMarchUse,
        "Depth interval from a raster of back faces: a ray hits a surface only between its "
        "depth and the back face of the same object behind it; --thickness where none is known"),
    field<&MarchSettings::ddaStride>("ddaStride", kMarchUse,
                                     "DDA marcher: pixels per step along the major axis")
        .floats(1.0, false),
    field<&MarchSettings::ddaJitter>(
        "ddaJitter", kMarchUse, "DDA marcher: random offset of the first step, in strides; 0 = off")
        .floats(0.0, false, 1.0),
    field<&MarchSettings::refineSteps>(
        "refineSteps", kMarchUse, "DDA marcher: binary-search steps between the last two samples")
        .ints(0, 32),
    field<&MarchSettings::hizMostDetailedLevel>(
        "hizMostDetailedLevel", kMarchUse,
        "Hi-Z marcher: finest level the traversal descends to (0 = full resolution)")
        .ints(0, kLastHiZLevel),
    field<&MarchSettings::hizStartLevel>(
        "hizStartLevel", kMarchUse,
        "Hi-Z marcher: level the traversal starts at (>= the most detailed level)")
        .ints(0, kLastHiZLevel),
};

// Every member is in the table.
static_assert(fieldCount<MarchSettings>() == kMarchFields.size(),
              "a MarchSettings member is missing from kMarchFields");

}  // namespace ssrt
