#include "io/write_options.h"

#include <iterator>

namespace ssrt {

namespace {

constexpr std::string_view kCompressionNames[] = {"none", "rle", "zips", "zip", "piz"};

std::string joined(const std::string_view* names, int n) {
    std::string out;
    for (int i = 0; i < n; ++i) out.append(i ? ", " : "").append(names[i]);
    return out;
}

}  // namespace

std::string_view exrCompressionName(ExrCompression c) { return kCompressionNames[int(c)]; }

std::optional<ExrCompression> parseExrCompression(std::string_view name) {
    for (int i = 0; i < int(std::size(kCompressionNames)); ++i)
        if (name == kCompressionNames[i]) return ExrCompression(i);
    return std::nullopt;
}

std::string exrCompressionList() {
    return joined(kCompressionNames, int(std::size(kCompressionNames)));
}

}  // namespace ssrt
