// How an image file is written: an EXR's compression (--exr-compression) and the threads that
// compress it. Names here are the command line's. (Which layers a file holds is the caller's
// choice: a frame's layer groups, `--layers`, are renderer/layer_groups.h.)
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace ssrt {

// OpenEXR's lossless compressions only: PXR24, B44(A) and DWAA/B would round or drop the
// float bits that ids and view depth need (B44 leaves float channels as they are, so it
// would only be "none" under another name).
enum class ExrCompression { None, Rle, Zips, Zip, Piz };
// The default: the 1080p all-layers frame (42 layers, 348 MB of floats) on 2 cores takes
// 0.7 s of CPU with RLE for a file of 61 % of the raw size; ZIP and PIZ make 35 % but take
// 4.3 and 2.6 s, none 0.2 s for 100 % (perf/README.md, "Image output and start-up").
inline constexpr ExrCompression kDefaultExrCompression = ExrCompression::Rle;

std::string_view exrCompressionName(ExrCompression c);  // "none", "rle", "zips", "zip", "piz"
std::optional<ExrCompression> parseExrCompression(std::string_view name);
std::string exrCompressionList();  // "none, rle, zips, zip, piz"

struct WriteOptions {
    ExrCompression compression = kDefaultExrCompression;
    int threads = 0;  // threads compressing an EXR; 0: every core
};

}  // namespace ssrt
