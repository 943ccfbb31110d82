// The packing keys of trace/march.cpp's sort, a lane group of rays at a time (the scalar loop
// it replaced cost about a third of the pass's packing and scatter).
#include "core/isa_target.h"
// (isa_target.h first: it names this copy's lane type)
#include "trace/march_common.h"

namespace ssrt::SSRT_ISA_NS {

namespace {

SSRT_INLINE Mask finite(Lane x) { return ln::abs(x) < Lane(__builtin_inff()); }

// Keys (as floats, -1 = no ray) of the rays at i .. i + kW - 1.
SSRT_INLINE Lane keys(const MarchKernelArgs& a, int i) {
    const Lane zero(0.0f), one(1.0f);
    const Lane pdf = ln::load<Lane>(a.pdf + i);
    const Lane ox = ln::load<Lane>(a.ox + i), oy = ln::load<Lane>(a.oy + i),
               oz = ln::load<Lane>(a.oz + i);
    const Lane dx = ln::load<Lane>(a.dx + i), dy = ln::load<Lane>(a.dy + i),
               dz = ln::load<Lane>(a.dz + i);
    const Mask valid = (pdf > zero) & finite(ox) & finite(oy) & finite(oz) & finite(dx) &
                       finite(dy) & finite(dz) & ((dx * dx + dy * dy) + dz * dz != zero) &
                       (zero - oz > zero);
    // The screen direction's "diamond angle" in [0, 4), binned into kSortSectors sectors.
    const Lane u = Lane(a.sx) * (ox * dz - dx * oz), v = Lane(a.sy) * (dy * oz - oy * dz);
    const Lane sum = ln::abs(u) + ln::abs(v);
    const Mask moving = sum > zero;
    const Lane r = v / ln::select(moving, sum, one);
    const Lane turned =
        ln::select(u >= zero, ln::select(v >= zero, r, Lane(4.0f) + r), Lane(2.0f) - r);
    const Lane angle = ln::select(moving, turned, zero);
    const Lane sector = ln::floor(
        ln::clamp(angle * Lane(0.25f * float(kSortSectors)), zero, Lane(float(kSortSectors - 1))));
    const Lane key = sector * Lane(2.0f) + ln::select(dz > zero, one, zero);
    return ln::select(valid, key, Lane(-1.0f));
}

}  // namespace

void marchSortKeys(const MarchKernelArgs& a) {
    alignas(64) float k[kW];
    for (int i = 0; i < a.count; i += kW) {
        ln::store(k, keys(a, i));
        for (int l = 0; l < kW && i + l < a.count; ++l) a.key[i + l] = int8_t(k[l]);
    }
}

}  // namespace ssrt::SSRT_ISA_NS
