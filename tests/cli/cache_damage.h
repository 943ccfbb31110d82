// Damage done to a reference cache entry by the tests (reference_cache_test.cpp, and the
// command's warnings in reference_cache_cli_test.cpp).
#pragma once

#include <cstdint>
#include <cstring>
#include <optional>
#include <string>

#include "cli/reference_cache.h"
#include "io/image_io.h"

namespace ssrt::test {

// The entry at `path` (width x height) with one bit of one value flipped and its header (key,
// checksum) kept: a file whose pixels changed on disk but that still reads. False if it could
// not be read.
inline bool flipPixelKeepHeader(const std::string& path, int width, int height, int plane, int x,
                                int y, int bit) {
    ReferenceImage ref;
    if (!cli::readReferenceImage(path, width, height, ref)) return false;
    float& v = cli::referencePlanes(ref)[std::size_t(plane)]->at(x, y);
    uint32_t bits = 0;
    std::memcpy(&bits, &v, 4);
    bits ^= 1u << bit;
    std::memcpy(&v, &bits, 4);
    const auto attrs = readExrStringAttributes(path);
    cli::writeReferenceImage(path, ref, std::nullopt,
                             {{cli::kCacheKeyAttribute, attrs.at(cli::kCacheKeyAttribute)},
                              {cli::kChecksumAttribute, attrs.at(cli::kChecksumAttribute)}});
    return true;
}

}  // namespace ssrt::test
