// OpenImageIO, loaded on first need (inside io/ only). Debian's OpenImageIO pulls in about
// 260 shared libraries (OpenCV, GDAL, FFmpeg, ...) that take a process 0.2-0.4 s to load, so
// no ssrt binary links it: io/oiio_plugin.cpp is built into the module ssrt_oiio.so, which is
// dlopen()ed the first time a file needs it (a format io/ does not decode itself).
#pragma once

#include <cstddef>
#include <string>

#include "io/decoded_image.h"

namespace ssrt::io_detail {

// The module's entry points. Errors come back as text (false and `error` set), not as
// exceptions, so nothing is thrown across the module's edge.
struct OiioModule {
    // Subimage 0, level 0: 8- and 16-bit files as they are stored, others as float.
    bool (*decodeFile)(const std::string& path, AlphaMode alpha, DecodedImage& out,
                       std::string& error);
    // `formatHint` is a file name or extension naming the format.
    bool (*decodeBytes)(const void* bytes, std::size_t size, const std::string& formatHint,
                        AlphaMode alpha, DecodedImage& out, std::string& error);
};

// The symbol the module exports: a function returning its table.
inline constexpr const char* kOiioModuleEntry = "ssrt_oiio_module_v1";
inline constexpr const char* kOiioModuleFile = "ssrt_oiio.so";

// The module, loaded once per process (thread-safe). Throws DecodeFailure, one line saying
// where it was looked for, when it cannot be found or loaded. Where: $SSRT_OIIO_MODULE if set;
// else beside the running program, in ../<libdir>/ssrt from it (an installed ssrt), and in
// the build tree it was built in.
const OiioModule& oiioModule();

}  // namespace ssrt::io_detail
