// The parts of an image (direct, specular, diffuse) for the per-component error, and the
// reference's composite. Internal to truth/.
#pragma once

#include "core/float_planes.h"
#include "core/isa.h"
#include "renderer/renderer.h"
#include "truth/reference_image.h"

namespace ssrt {

// specular = specWeight (ssr opacity + envSpecular (1 - opacity)); diffuse = albedo
// (1 - metallic) ssgi, 0 on background: the composite's arithmetic (shading/composite_kernel.cpp),
// so that the parts and emission add up to its colour. Planes of the frame's size.
void specularDiffuse(const Frame& frame, const FloatPlane ssr[3], const PlaneF& opacity,
                     const FloatPlane ssgi[3], PlaneF specular[3], PlaneF diffuse[3]);

// Fills ref.color (composite of ref.direct, ref.ssr with opacity 1 on surfaces, ref.ssgi and
// the frame's emission, sky diffuse, sky specular and split-sum factor) and ref.specular and
// ref.diffuse, from ref.direct, ref.ssr and ref.ssgi.
void composeReference(Isa isa, const Frame& frame, float exposure, bool anyEmissive, int threads,
                      ReferenceImage& ref);

}  // namespace ssrt
