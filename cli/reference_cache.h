// The reference image for a request, from the cache when it holds one, else rendered (with
// progress) and stored. Files are EXRs named by referenceKey() (truth/
// reference_image.h), so any change to the scene or to a setting that shapes the reference
// makes a new file. Each entry also holds its key and a checksum of its pixels in its header,
// so that a file damaged on disk (truncated, bits flipped) or another key's file under this
// name is found on reading, warned about, and rendered again; nothing is ever read back for a
// different request.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "renderer/renderer.h"
#include "truth/reference_image.h"
#include "world/embree_scene.h"

namespace ssrt::cli {

// $SSRT_CACHE_DIR, else $XDG_CACHE_HOME/ssrt, else $HOME/.cache/ssrt (empty if none is set).
std::string defaultCacheDir();

struct ReferenceSource {
    std::optional<std::string> cacheDir;  // nullopt: no cache (always render, store nothing)
    std::ostream* progress = nullptr;     // "reference: 40%" (cli/progress_line.h); null: quiet
    std::ostream* warnings = nullptr;     // a damaged cache entry, one line; null: none
};

// The reference for `settings` (its trace settings' SSR sampler and frame index; both trace
// passes are turned on for the frame it is rendered over). `fromCache` tells where it came
// from. A cache file that is not whole and this request's (readCacheEntry) is rendered again
// and replaced, with one line on `source.warnings` naming it and what was wrong.
// With `band`, a cached whole reference is returned as it is, else only the band's rows are
// rendered (renderReference) and nothing is stored: a band is not the whole reference.
// Cache files are written to a temporary of a name unique to the process and renamed over
// the target, so processes on many machines sharing one cache folder (a Slurm array's tasks)
// never see a torn file: readers get a whole reference or none, and of two writers racing
// on one key the last rename wins with a file as whole (and as identical) as the other's.
ReferenceImage referenceFor(const EmbreeScene& embree, const Scene& scene, const FrameInput& input,
                            const RenderSettings& settings, const ReferenceSettings& reference,
                            const ReferenceSource& source, bool& fromCache,
                            std::optional<RowBand> band = std::nullopt);

// The same with the request's key (truth's referenceKey) already computed: it hashes the
// whole scene, textures included, so a caller that needs the key as well computes it once.
ReferenceImage referenceForKey(uint64_t key, const EmbreeScene& embree, const Scene& scene,
                               const FrameInput& input, const RenderSettings& settings,
                               const ReferenceSettings& reference, const ReferenceSource& source,
                               bool& fromCache, std::optional<RowBand> band = std::nullopt);

// The reference's planes as files name them (the cache's, `ssrt reference -o`'s): ref.color.R,
// .G, .B, then ref.direct, ref.ssr, ref.ssgi, ref.specular, ref.diffuse likewise.
std::vector<std::string> referenceChannelNames();
// Writes `ref` as an EXR of referenceChannelNames(), whole or not at all; with `band` only its
// rows (an image band.y1 - band.y0 rows high), with `attributes` in the header.
void writeReferenceImage(const std::string& path, const ReferenceImage& ref,
                         std::optional<RowBand> band = std::nullopt,
                         std::vector<std::pair<std::string, std::string>> attributes = {});
// The planes of `ref` in the order of referenceChannelNames().
std::vector<PlaneF*> referencePlanes(ReferenceImage& ref);
std::vector<const PlaneF*> referencePlanes(const ReferenceImage& ref);
// The cache's file name for a key: ref-<16 hex digits>.exr.
std::string referenceCacheFileName(uint64_t key);
// The key of such a name; throws std::runtime_error naming it for any other name.
uint64_t referenceKeyOfCacheFileName(const std::string& name);
// Reads one back: false (and `ref` unspecified) if the file is missing, unreadable, lacks a
// plane or is not width x height.
bool readReferenceImage(const std::string& path, int width, int height, ReferenceImage& ref);

// A cache entry's header attributes: its key (16 hex digits, as in its name) and a checksum of
// its pixels (16 hex digits: FNV-1a 64 over every plane's values in referenceChannelNames()
// order, core/image.h hashPlane). Entries of ssrt before them have neither and are rendered
// again once, with a warning.
inline constexpr const char* kCacheKeyAttribute = "ssrtCacheKey";
inline constexpr const char* kChecksumAttribute = "ssrtPixelChecksum";
uint64_t referenceChecksum(const ReferenceImage& ref);

// Writes `ref` as the cache's entry for `key` in `cacheDir` (made if missing), with its key and
// checksum, whole or not at all (a temporary renamed over the entry: of two processes writing
// one key at once, the last rename wins, and either file is whole). Returns its path.
std::string writeCacheEntry(const std::string& cacheDir, uint64_t key, const ReferenceImage& ref);
// Reads the entry at `path` for `key` into `ref`: nullopt when it is there, whole and this
// key's; otherwise what is wrong, for a warning: "missing" for no file (no warning due), else
// "cannot be read (...)", "is 32 x 18 pixels, not 64 x 36", "holds no key or checksum (an
// older ssrt's entry)", "is the entry of key ..., not ..." (another request's file), "its
// pixels do not match their checksum (damaged)".
std::optional<std::string> readCacheEntry(const std::string& path, uint64_t key, int width,
                                          int height, ReferenceImage& ref);
inline constexpr const char* kCacheEntryMissing = "missing";

}  // namespace ssrt::cli
