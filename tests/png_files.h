// PNG files of any colour type, bit depth and chunk, written through libpng for the decoder
// tests (OpenImageIO writes only 8- and 16-bit grey and RGB(A), none with a palette,
// transparency chunk, interlacing or gamma).
#pragma once

#include <png.h>

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace ssrt::test {

struct PngSpec {
    int width = 5, height = 3;
    int colourType = PNG_COLOR_TYPE_RGB;
    int bitDepth = 8;
    bool interlaced = false;
    bool transparency = false;  // a tRNS chunk
    double gamma = 0.0;         // a gAMA chunk when > 0
    bool srgbChunk = false;     // an sRGB chunk, with its gAMA and cHRM
};

// Row bytes as the file stores them (packed below 8 bits, big-endian 16-bit), filled from a
// fixed sequence so every sample value range is used.
inline std::vector<uint8_t> pngRows(const PngSpec& s, std::size_t rowBytes) {
    std::vector<uint8_t> bytes(rowBytes * std::size_t(s.height));
    uint32_t state = 12345u;
    for (uint8_t& b : bytes) {
        state = state * 1664525u + 1013904223u;
        b = uint8_t(state >> 24);
    }
    return bytes;
}

// Writes the PNG; a palette image gets 2^bitDepth colours, so every index is valid. A test helper:
// libpng's errors end the test run (its default handler).
inline void writePng(const std::string& path, const PngSpec& s) {
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) throw std::runtime_error("test could not write " + path);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, file);
    png_set_IHDR(png, info, s.width, s.height, s.bitDepth, s.colourType,
                 s.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    const int entries = 1 << s.bitDepth;
    std::vector<png_color> palette(static_cast<std::size_t>(entries));
    std::vector<png_byte> alphas(static_cast<std::size_t>(entries));
    for (int i = 0; i < entries; ++i) {
        palette[i] = {png_byte(i * 37), png_byte(255 - i * 11), png_byte(i * 101)};
        alphas[i] = png_byte(255 - i * 53);
    }
    if (s.colourType == PNG_COLOR_TYPE_PALETTE) png_set_PLTE(png, info, palette.data(), entries);
    if (s.transparency) {
        png_color_16 key{0, 3, 5, 7, 1};  // grey 1 (grey images), RGB (3, 5, 7)
        png_set_tRNS(png, info, alphas.data(), s.colourType == PNG_COLOR_TYPE_PALETTE ? entries : 0,
                     &key);
    }
    if (s.gamma > 0.0) png_set_gAMA(png, info, s.gamma);
    if (s.srgbChunk) png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    std::vector<uint8_t> rows = pngRows(s, png_get_rowbytes(png, info));
    std::vector<png_bytep> pointers;
    for (int y = 0; y < s.height; ++y)
        pointers.push_back(rows.data() + std::size_t(y) * png_get_rowbytes(png, info));
    png_write_image(png, pointers.data());
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
}

}  // namespace ssrt::test
