// `ssrt reference`: the Embree reference image of one frame (the one `ssrt compare` measures a
// single frame against) written as an EXR of ref.* layers and kept in the reference cache.
// With --shard K/N it renders band K of N of the frame's rows (whole tile rows) into
// NAME.shard-K-of-N.exr; `ssrt merge` assembles the bands into the very file (bit for bit)
// the unsharded command writes, and can put it in the cache for compare and sweep to find.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>

#include "cli/compare_command.h"

namespace CLI {
class App;
}

namespace ssrt::cli {

// The header attributes of a band's file (ImageLayers::attributes), read back by merge.
inline constexpr const char* kPartAttribute = "ssrtPart";    // "reference"
inline constexpr const char* kShardAttribute = "ssrtShard";  // "K/N"
inline constexpr const char* kRowsAttribute = "ssrtRows";    // "y0 y1" of the whole image
inline constexpr const char* kSizeAttribute = "ssrtSize";    // "W H" of the whole image
inline constexpr const char* kKeyAttribute = "ssrtKey";      // the cache's file name
inline constexpr const char* kReferencePart = "reference";

struct ReferenceOptions {
    RenderOptions render;  // the scene and the frame's settings (SSR sampler, march reach, ...)
    TruthOptions truth;    // the reference's own settings, the cache
    std::string output = "reference.exr";
    std::optional<std::string> shard;
};

CLI::App* addReferenceCommand(CLI::App& app, ReferenceOptions& options);
int runReference(const ReferenceOptions& options, std::ostream& out, std::ostream& err);

}  // namespace ssrt::cli
