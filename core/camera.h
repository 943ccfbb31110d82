// The pinhole camera of a frame as plain numbers: what the screen-space tracer (trace/) and
// the denoiser (denoise/) both read, so it lives below both.
//
// View space is the camera's: x right, y up, the camera looks down -z. A G-buffer `viewZ`
// is the positive distance along -z (0 for background), so a point at pixel (px, py) with
// depth z sits at ((2 (px + 0.5) / width - 1) tanHalfX z, (1 - 2 (py + 0.5) / height)
// tanHalfY z, -z). Pixel rows run top to bottom.
#pragma once

namespace ssrt {

struct TraceCamera {
    int width = 0, height = 0;
    float tanHalfX = 1.0f, tanHalfY = 1.0f;  // view ray at NDC (x, y): (x tanHalfX, y tanHalfY, -1)
    float nearZ = 0.05f, farZ = 100.0f;      // positive distances
    // Where in its pixel each pixel's sample lies, in pixels: the centre (0.5, 0.5), but on
    // a half frame its block's chosen pixel (trace/trace_layout.h: halfPixelPoint). Ray
    // generation starts rays there and the march projects with it; the other passes read
    // a half frame through their own guides and take pixel centres.
    float pointX = 0.5f, pointY = 0.5f;
    float viewToWorld[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // rotation, column-major
    // World positions in the passes and the truth are measured from `origin` (the scene's
    // bounds centre, Scene::origin()): a point is origin + position + viewToWorld * view.
    // The marchers read neither.
    float position[3] = {0, 0, 0};  // the camera, from the origin
    float origin[3] = {0, 0, 0};
    // The diagonal of the scene's bounding box (world units): the unit of the march's
    // relative lengths (MarchSettings::maxDistance); 0 where nobody set it.
    float sceneDiagonal = 0.0f;
};

}  // namespace ssrt
