#include "core/plane_check.h"

#include <stdexcept>

namespace ssrt {

template <class T>
void PlaneCheck::check(const Plane<T>* p, std::string_view what) {
    const std::string name = pass_ + ": " + std::string(what);
    if (!p || p->empty()) throw std::invalid_argument(name + " is missing");
    if (p->width() != width_ || p->height() != height_)
        throw std::invalid_argument(name + " is " + std::to_string(p->width()) + "x" +
                                    std::to_string(p->height()) + ", not " +
                                    std::to_string(width_) + "x" + std::to_string(height_));
    stride_ = p->stride();
}
template void PlaneCheck::check(const PlaneF*, std::string_view);
template void PlaneCheck::check(const PlaneU16*, std::string_view);

}  // namespace ssrt
