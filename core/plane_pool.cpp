#include "core/plane_pool.h"

#include "core/pixel_formats.h"

namespace ssrt {

namespace {

void fill(PlaneF& p, float value) { p.fill(value); }
void fill(PlaneU16& p, float value) { p.fill(encodeF16(value)); }
void fill(PlaneU64& p, float value) { p.fill(0x0001000100010001ull * encodeF16(value)); }

template <class T>
void takePlane(Plane<T>& p, int width, int height, std::optional<float> poison) {
    if (p.width() == width && p.height() == height && !p.empty()) return;
    p.ensureSize(width, height);
    if (poison) fill(p, *poison);
}

}  // namespace

void PlanePool::take(PlaneF& p, int width, int height) { takePlane(p, width, height, poison_); }
void PlanePool::take(PlaneU16& p, int width, int height) { takePlane(p, width, height, poison_); }
void PlanePool::take(PlaneU64& p, int width, int height) { takePlane(p, width, height, poison_); }
void PlanePool::give(PlaneF& p) { p = PlaneF(); }
void PlanePool::give(PlaneU16& p) { p = PlaneU16(); }
void PlanePool::give(PlaneU64& p) { p = PlaneU64(); }

}  // namespace ssrt
