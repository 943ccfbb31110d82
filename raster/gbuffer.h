// The G-buffer: attributes of the visible surface at each pixel, built by the resolve pass.
#pragma once

#include "core/image.h"

namespace ssrt {

struct GBuffer {
    PlaneF viewZ;                        // distance along the view axis; 0 = background
    PlaneF normalX, normalY, normalZ;    // world-space unit normal, facing the camera
    PlaneF albedoR, albedoG, albedoB;    // base colour (linear)
    PlaneF metallic, roughness;          // roughness is perceptual
    PlaneF materialId, instanceId, triangleId;  // -1 = background
    PlaneF motionX, motionY;             // previous minus current position, in pixels
};

}  // namespace ssrt
