#include "cli/reference_cache.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <ostream>
#include <stdexcept>

#include "cli/cli.h"
#include "cli/progress_line.h"
#include "core/image.h"
#include "io/image_io.h"

namespace ssrt::cli {

namespace fs = std::filesystem;

namespace {

// The reference's planes as the cache file names them.
struct RefPlane {
    const char* name;
    PlaneF (ReferenceImage::*group)[3];
};
constexpr RefPlane kGroups[] = {
    {"ref.color", &ReferenceImage::color},       {"ref.direct", &ReferenceImage::direct},
    {"ref.ssr", &ReferenceImage::ssr},           {"ref.ssgi", &ReferenceImage::ssgi},
    {"ref.specular", &ReferenceImage::specular}, {"ref.diffuse", &ReferenceImage::diffuse},
};
constexpr const char* kSuffix[3] = {".R", ".G", ".B"};

}  // namespace

std::vector<std::string> referenceChannelNames() {
    std::vector<std::string> names;
    for (const RefPlane& g : kGroups)
        for (int c = 0; c < 3; ++c) names.push_back(std::string(g.name) + kSuffix[c]);
    return names;
}

namespace {

// ReferenceImage or const ReferenceImage: the planes with its constness.
template <class Image>
auto planesOf(Image& ref) {
    std::vector<decltype(&ref.color[0])> planes;
    for (const RefPlane& g : kGroups)
        for (int c = 0; c < 3; ++c) planes.push_back(&(ref.*g.group)[c]);
    return planes;
}

}  // namespace

std::vector<PlaneF*> referencePlanes(ReferenceImage& ref) { return planesOf(ref); }
std::vector<const PlaneF*> referencePlanes(const ReferenceImage& ref) { return planesOf(ref); }

std::string referenceCacheFileName(uint64_t key) {
    char name[40];
    std::snprintf(name, sizeof name, "ref-%016llx.exr", static_cast<unsigned long long>(key));
    return name;
}

uint64_t referenceKeyOfCacheFileName(const std::string& name) {
    const bool ok =
        name.size() == 24 && name.rfind("ref-", 0) == 0 && name.compare(20, 4, ".exr") == 0 &&
        std::all_of(name.begin() + 4, name.begin() + 20,
                    [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
    if (!ok) throw std::runtime_error("'" + name + "': not a reference cache file name");
    return std::stoull(name.substr(4, 16), nullptr, 16);
}

namespace {

// A file's channels (referenceChannelNames() order, each w x h) into `ref`'s planes.
void fillPlanes(const std::vector<std::vector<float>>& channels, int w, int h,
                ReferenceImage& ref) {
    const std::vector<PlaneF*> planes = referencePlanes(ref);
    for (std::size_t k = 0; k < planes.size(); ++k) {
        *planes[k] = PlaneF(w, h);
        for (int y = 0; y < h; ++y)
            std::copy_n(channels[k].data() + std::size_t(y) * w, w, planes[k]->row(y));
    }
}

std::string hex16(uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

}  // namespace

bool readReferenceImage(const std::string& path, int width, int height, ReferenceImage& ref) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return false;
    try {
        // One read for every plane: the file is decompressed once.
        int w = 0, h = 0;
        const std::vector<std::vector<float>> channels =
            readChannels(path, referenceChannelNames(), w, h);
        if (w != width || h != height) return false;
        fillPlanes(channels, w, h, ref);
    } catch (const std::exception&) {
        return false;  // unreadable or incomplete
    }
    return true;
}

uint64_t referenceChecksum(const ReferenceImage& ref) {
    uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a's offset basis, chained plane to plane
    for (const PlaneF* p : referencePlanes(ref)) h = hashPlane(*p, h);
    return h;
}

std::optional<std::string> readCacheEntry(const std::string& path, uint64_t key, int width,
                                          int height, ReferenceImage& ref) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return std::string(kCacheEntryMissing);
    std::map<std::string, std::string> attributes;
    std::vector<std::vector<float>> channels;
    int w = 0, h = 0;
    try {
        attributes = readExrStringAttributes(path);
        channels = readChannels(path, referenceChannelNames(), w, h);
    } catch (const std::exception& e) {
        return "cannot be read (" + oneLine(e.what()) + ")";
    }
    const auto keyIt = attributes.find(kCacheKeyAttribute);
    const auto sumIt = attributes.find(kChecksumAttribute);
    if (keyIt == attributes.end() || sumIt == attributes.end())
        return std::string("holds no key or checksum (an older ssrt's entry)");
    if (keyIt->second != hex16(key))
        return "is the entry of key " + keyIt->second + ", not " + hex16(key) +
               " (another request's file under its name)";
    if (w != width || h != height)
        return "is " + std::to_string(w) + " x " + std::to_string(h) + " pixels, not " +
               std::to_string(width) + " x " + std::to_string(height);
    fillPlanes(channels, w, h, ref);
    if (sumIt->second != hex16(referenceChecksum(ref)))
        return std::string("its pixels do not match their checksum (damaged)");
    return std::nullopt;
}

void writeReferenceImage(const std::string& path, const ReferenceImage& ref,
                         std::optional<RowBand> band,
                         std::vector<std::pair<std::string, std::string>> attributes) {
    const int width = ref.color[0].width();
    const RowBand rows = band.value_or(RowBand{0, ref.color[0].height()});
    ImageLayers image{width, rows.y1 - rows.y0, {}, std::move(attributes)};
    const std::vector<std::string> names = referenceChannelNames();  // alive while viewed
    const std::vector<const PlaneF*> planes = referencePlanes(ref);
    std::vector<PlaneF> cropped;  // a band's rows, copied out
    cropped.reserve(planes.size());
    for (std::size_t k = 0; k < planes.size(); ++k) {
        const PlaneF* plane = planes[k];
        if (band) {
            cropped.emplace_back(width, image.height);
            for (int y = rows.y0; y < rows.y1; ++y)
                std::copy_n(plane->row(y), width, cropped.back().row(y - rows.y0));
            plane = &cropped.back();
        }
        image.layers.push_back({names[k], plane});
    }
    writeImage(path, image);  // whole or not at all (a temporary renamed over the target)
}

std::string writeCacheEntry(const std::string& cacheDir, uint64_t key, const ReferenceImage& ref) {
    fs::create_directories(cacheDir);
    const std::string path = (fs::path(cacheDir) / referenceCacheFileName(key)).string();
    writeReferenceImage(
        path, ref, std::nullopt,
        {{kCacheKeyAttribute, hex16(key)}, {kChecksumAttribute, hex16(referenceChecksum(ref))}});
    return path;
}

std::string defaultCacheDir() {
    if (const char* d = std::getenv("SSRT_CACHE_DIR"); d && *d) return d;
    if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d)
        return (fs::path(d) / "ssrt").string();
    if (const char* d = std::getenv("HOME"); d && *d)
        return (fs::path(d) / ".cache" / "ssrt").string();
    return {};
}

namespace {

// Renders the reference (or a band of it) over the frame `input` gives: its G-buffer, direct
// parts and shadow map, both trace passes on.
ReferenceImage renderFresh(const EmbreeScene& embree, const Scene& scene, const FrameInput& input,
                           const RenderSettings& settings, const ReferenceSettings& reference,
                           const ReferenceSource& source, std::optional<RowBand> band) {
    RenderSettings base = settings;
    base.trace.ssr = base.trace.ssgi = true;
    const Renderer renderer(base);
    Frame frame;
    renderer.renderWithoutHistory(scene, input, frame);
    if (!source.progress) return renderReference(embree, renderer, frame, reference, {}, band);
    ProgressLine line(*source.progress, "reference");
    return renderReference(
        embree, renderer, frame, reference, [&line](double fraction) { line.update(fraction); },
        band);
}

}  // namespace

ReferenceImage referenceFor(const EmbreeScene& embree, const Scene& scene, const FrameInput& input,
                            const RenderSettings& settings, const ReferenceSettings& reference,
                            const ReferenceSource& source, bool& fromCache,
                            std::optional<RowBand> band) {
    const uint64_t key = referenceKey(scene, input.camera, input.frameIndex, settings, reference);
    return referenceForKey(key, embree, scene, input, settings, reference, source, fromCache, band);
}

ReferenceImage referenceForKey(uint64_t key, const EmbreeScene& embree, const Scene& scene,
                               const FrameInput& input, const RenderSettings& settings,
                               const ReferenceSettings& reference, const ReferenceSource& source,
                               bool& fromCache, std::optional<RowBand> band) {
    fromCache = false;
    const std::string path =
        source.cacheDir ? (fs::path(*source.cacheDir) / referenceCacheFileName(key)).string()
                        : std::string();
    ReferenceImage ref;
    if (!path.empty()) {
        const std::optional<std::string> problem =
            readCacheEntry(path, key, settings.width, settings.height, ref);
        if (!problem) {
            fromCache = true;
            return ref;
        }
        if (*problem != kCacheEntryMissing && source.warnings)
            *source.warnings << "ssrt: warning: reference cache: '" << path << "' " << *problem
                             << ": rendering it again\n";
    }
    ref = renderFresh(embree, scene, input, settings, reference, source, band);
    if (source.cacheDir && !band) {  // a band is not the whole reference: never cached
        try {
            writeCacheEntry(*source.cacheDir, key, ref);
        } catch (const std::exception& e) {
            // A cache that cannot be written costs time, not the answer.
            if (source.progress) *source.progress << "reference: not cached (" << e.what() << ")\n";
        }
    }
    return ref;
}

}  // namespace ssrt::cli
