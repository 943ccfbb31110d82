#include "trace/trace_types.h"

namespace ssrt {

void RayBatch::ensureSize(int width, int height) {
    for (PlaneF* p : {&ox, &oy, &oz, &dx, &dy, &dz, &pdf}) p->ensureSize(width, height);
}

void MarchResult::ensureSize(int width, int height) {
    for (PlaneF* p : {&hit, &hitX, &hitY, &hitZ, &steps, &cause}) p->ensureSize(width, height);
}

}  // namespace ssrt
