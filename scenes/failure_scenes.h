// Built-in scenes that show where screen-space tracing fails, one failure mode each.
// Instances are found by their material's name (the tests rely on it): see each builder.
#pragma once

#include "scenes/scene.h"

namespace ssrt {

inline constexpr const char* kThinDescription =
    "slabs 3 mm to 5 cm thick and 1 m tall on a mirror floor, seen from low down; tests the "
    "depth-thickness guess (reflected rays pass behind thin objects)";
inline constexpr const char* kFenceDescription =
    "a fence of 2.5 cm poles and 1 cm wires, about a pixel wide at 320x180, before a blue wall "
    "on a mirror floor; tests geometry thinner than a march step (skipped) and than the "
    "thickness guess (false hits behind it)";
inline constexpr const char* kCorridorDescription =
    "a glossy corridor 30 m long and 3 m wide, open to the sky (no ceiling), objects along "
    "it; tests long rays and grazing angles";
inline constexpr const char* kOffscreenDescription =
    "bright emissive spheres just above the top of the view, reflected by a mirror floor; "
    "tests rays that leave the screen";
inline constexpr const char* kOccludedDescription =
    "a side mirror shows a sphere that a box hides from the camera; tests missing depth "
    "layers (the reflected surface is in no pixel)";

// Slabs (materials "post_0".."post_5", thinnest first) on a mirror floor ("mirror_floor").
Scene makeThinScene();
// Poles ("fence_pole"), wires ("fence_wire"), the wall behind ("fence_wall") on a mirror
// floor ("mirror_floor").
Scene makeFenceScene();
// Floor ("corridor_floor"), walls ("corridor_wall"), far end ("corridor_end"); no ceiling.
Scene makeCorridorScene();
// Mirror floor ("mirror_floor"); emitters "lamp_*" above the frustum; props in view.
Scene makeOffscreenScene();
// Mirror wall ("mirror_wall"), the hidden sphere ("hidden") and the box ("occluder").
Scene makeOccludedScene();

}  // namespace ssrt
