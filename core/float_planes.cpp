#include "core/float_planes.h"

namespace ssrt {

PlaneF decodedF16(const PlaneU16& p) {
    PlaneF out(p.width(), p.height(), kUninitialized);
    for (int y = 0; y < p.height(); ++y) {
        const uint16_t* in = p.row(y);
        float* to = out.row(y);
        for (int x = 0; x < p.width(); ++x) to[x] = decodeF16(in[x]);
    }
    return out;
}

PlaneU16 f16x4Channel(const PlaneU64& p, int channel) {
    PlaneU16 out(p.width(), p.height(), kUninitialized);
    for (int y = 0; y < p.height(); ++y) {
        const uint64_t* in = p.row(y);
        uint16_t* to = out.row(y);
        for (int x = 0; x < p.width(); ++x) to[x] = uint16_t(in[x] >> (16 * channel));
    }
    return out;
}

}  // namespace ssrt
