#include "core/plane_view.h"

#include <span>
#include <stdexcept>
#include <string>

namespace ssrt {

std::size_t requireViews(std::string_view pass, int width, int height, const ViewShape* views,
                         std::size_t count) {
    std::size_t stride = 0;
    for (const ViewShape& v : std::span(views, count)) {
        const std::string what = std::string(pass) + ": " + std::string(v.name);
        if (!v.data || v.width == 0 || v.height == 0)
            throw std::invalid_argument(what + " is missing");
        if (v.width != width || v.height != height)
            throw std::invalid_argument(what + " is " + std::to_string(v.width) + "x" +
                                        std::to_string(v.height) + ", not " +
                                        std::to_string(width) + "x" + std::to_string(height));
        stride = v.stride;  // one size, one stride (core/image.h)
    }
    return stride;
}

}  // namespace ssrt
