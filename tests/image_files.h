// Small image files that tests write themselves (8- or 16-bit PNG, through OpenImageIO),
// and a file's bytes, for images embedded in glTF files.
#pragma once

#include <OpenImageIO/imageio.h>

#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace ssrt::test {

// Writes `values` (w * h * channels, row 0 first) to `path`; T is uint8_t or uint16_t.
template <class T>
void writeImage(const std::string& path, int w, int h, int channels, const std::vector<T>& values) {
    auto out = OIIO::ImageOutput::create(path);
    OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDescFromC<T>::value());
    spec.attribute("oiio:UnassociatedAlpha", 1);  // store the values as given
    if (!out || !out->open(path, spec) ||
        !out->write_image(OIIO::TypeDescFromC<T>::value(), values.data()) || !out->close())
        throw std::runtime_error("test could not write " + path);
}

inline std::vector<unsigned char> fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace ssrt::test
