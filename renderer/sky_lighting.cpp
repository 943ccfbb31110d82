#include "renderer/sky_lighting.h"

#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>

#include "shading/prefiltered_env.h"

namespace ssrt {

SkyImage makeSkyImage(std::string source, InterleavedImage rgb) {
    if (rgb.channels != 3 || rgb.width < 1 || rgb.height < 1 ||
        rgb.pixels.size() != std::size_t(3) * rgb.width * rgb.height)
        throw std::invalid_argument("sky image '" + source + "': not " + std::to_string(rgb.width) +
                                    "x" + std::to_string(rgb.height) + " RGB");
    SkyImage img;
    img.source = std::move(source);
    img.width = rgb.width;
    img.height = rgb.height;
    img.rgb = std::move(rgb.pixels);
    // Box-filter to half size until the renderer's float texel indices are exact.
    while (std::size_t(img.width) * img.height > kSkyMaxTexels) {
        EquirectImage half =
            downsampleBox(EquirectView{img.rgb.data(), img.width, img.height, nullptr, nullptr});
        img.width = half.width;
        img.height = half.height;
        img.rgb = std::move(half.rgb);
    }
    return img;
}

EquirectView SkyLighting::level(const SkyImage& image, int i) const {
    if (i == 0)
        return {image.rgb.data(), image.width, image.height, poleTop.data(), poleBottom.data()};
    return prefiltered[i - 1].view();
}

SkyLighting buildSkyLighting(const SkyImage& image, int threads) {
    SkyLighting out;
    const EquirectView source{image.rgb.data(), image.width, image.height, nullptr, nullptr};
    // Poles of the image itself: the mean of its first and last rows (as EquirectImage does).
    for (int c = 0; c < 3; ++c) {
        double top = 0.0, bottom = 0.0;
        for (int x = 0; x < image.width; ++x) {
            top += image.rgb[std::size_t(x) * 3 + c];
            bottom += image.rgb[(std::size_t(image.height - 1) * image.width + x) * 3 + c];
        }
        out.poleTop[c] = float(top / image.width);
        out.poleBottom[c] = float(bottom / image.width);
    }
    // A copy at most kSkyPrefilterWidth wide, by box filtering.
    EquirectImage base;
    if (image.width <= kSkyPrefilterWidth) {
        base = EquirectImage(image.width, image.height, image.rgb);
    } else {
        base = downsampleBox(source);
        while (base.width > kSkyPrefilterWidth) base = downsampleBox(base);
    }
    out.irradiance = projectIrradianceSh(base.view());
    PrefilterSettings ps;
    ps.levels = kSkyLevels;
    ps.threads = threads;
    PrefilteredEnvironment pre(Environment::equirect(base.width, base.height, std::move(base.rgb)),
                               ps);
    for (int i = 1; i < pre.levelCount(); ++i) out.prefiltered.push_back(pre.level(i));
    return out;
}

namespace {

struct CacheEntry {
    std::weak_ptr<const SkyImage> image;
    std::shared_ptr<const SkyLighting> lighting;
};

std::mutex& cacheMutex() {
    static std::mutex m;
    return m;
}

std::vector<CacheEntry>& cacheEntries() {
    static std::vector<CacheEntry> entries;
    return entries;
}

void dropDead(std::vector<CacheEntry>& entries) {
    entries.erase(std::remove_if(entries.begin(), entries.end(),
                                 [](const CacheEntry& e) { return e.image.expired(); }),
                  entries.end());
}

}  // namespace

std::shared_ptr<const SkyLighting> cachedSkyLighting(const std::shared_ptr<const SkyImage>& image,
                                                     int threads, bool* built) {
    if (built) *built = false;
    if (!image) return nullptr;
    // One lock over lookup and build: a second caller with the same image waits for the
    // first build instead of repeating it.
    std::lock_guard<std::mutex> lock(cacheMutex());
    std::vector<CacheEntry>& entries = cacheEntries();
    dropDead(entries);
    for (const CacheEntry& e : entries)
        if (!e.image.owner_before(image) && !image.owner_before(e.image)) return e.lighting;
    // Isolated, so that while this thread waits inside the build's parallel loop it cannot
    // pick up another render's task that would wait for this lock.
    auto lighting = std::make_shared<const SkyLighting>(
        tbb::this_task_arena::isolate([&] { return buildSkyLighting(*image, threads); }));
    entries.push_back({image, lighting});
    if (built) *built = true;
    return lighting;
}

int skyLightingCacheSize() {
    std::lock_guard<std::mutex> lock(cacheMutex());
    dropDead(cacheEntries());
    return int(cacheEntries().size());
}

}  // namespace ssrt
