// A small multi-layer float image that tests build plane by plane and write as an EXR
// through io/image_io.h (the renderer's own writer), for the image comparison tests.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"
#include "io/image_io.h"

namespace ssrt::test {

struct LayeredImage {
    int width = 0, height = 0;
    std::vector<std::pair<std::string, PlaneF>> planes;  // channel name, values

    LayeredImage(int w, int h, const std::vector<std::string>& names) : width(w), height(h) {
        // Distinct, ordinary values: channel c at (x, y) is 0.1 + 0.05 c + 0.01 (x + w y).
        for (std::size_t c = 0; c < names.size(); ++c) {
            PlaneF plane(w, h);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x)
                    plane.at(x, y) = 0.1f + 0.05f * float(c) + 0.01f * float(x + w * y);
            planes.emplace_back(names[c], std::move(plane));
        }
    }
    float& at(const std::string& name, int x, int y) {
        for (auto& [n, plane] : planes)
            if (n == name) return plane.at(x, y);
        throw std::logic_error("test image has no channel " + name);
    }
    void write(const std::string& path) const {
        ImageLayers layers{width, height, {}};
        for (const auto& [name, plane] : planes) layers.layers.push_back({name, &plane});
        writeImage(path, layers, WriteOptions{ExrCompression::Zips, 1});
    }
};

}  // namespace ssrt::test
