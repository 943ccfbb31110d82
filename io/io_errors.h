// The one-line errors of io/'s readers and writers (inside io/ only): OpenImageIO's and
// OpenEXR's messages may span lines; ours are one line each, naming the file.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ssrt::io_detail {

inline std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text.empty() ? "unknown error" : text;
}

[[noreturn]] inline void failWrite(const std::string& path, const std::string& reason) {
    throw std::runtime_error("cannot write '" + path + "': " + oneLine(reason));
}

[[noreturn]] inline void failRead(const std::string& path, const std::string& reason) {
    throw std::runtime_error("cannot read '" + path + "': " + oneLine(reason));
}

// A decoder's failure, the reason alone (io/image_decode.h): each public reader words it with
// the name of the file or image in its own way.
struct DecodeFailure : std::runtime_error {
    using std::runtime_error::runtime_error;
};

[[noreturn]] inline void failDecode(const std::string& reason) {
    throw DecodeFailure(oneLine(reason));
}

}  // namespace ssrt::io_detail
