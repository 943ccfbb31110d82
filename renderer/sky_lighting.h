// What the direct-light pass derives from an equirectangular sky image, built once per image
// and cached by the image's identity (not per frame, not per renderer).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "scenes/scene.h"
#include "shading/environment.h"
#include "shading/irradiance_sh.h"

namespace ssrt {

// The most texels an image sky holds: the environment's float texel indices are exact below
// 2^24 (shading/environment.h; Scene::validate refuses more).
inline constexpr std::size_t kSkyMaxTexels = std::size_t(1) << 24;

// An image sky from decoded RGB (3 channels, linear, finite and >= 0: io/image_io.h
// readSkyImage), `source` naming where it came from. An image larger than kSkyMaxTexels
// (above 8192 x 2048) is box-filtered to half size (shading/environment.h downsampleBox)
// until it fits. Throws std::invalid_argument for an image that is not 3-channel RGB of its
// size.
SkyImage makeSkyImage(std::string source, InterleavedImage rgb);

inline constexpr int kSkyLevels = 7;            // roughness levels 0, 1/6, ..., 1
inline constexpr int kSkyPrefilterWidth = 512;  // prefilter and SH from a copy at most this wide

// Level 0 is the image itself (borrowed: the caller keeps the SkyImage alive), level i > 0 the
// GGX-prefiltered environment at perceptual roughness i / (kSkyLevels - 1) (Karis 2013, see
// shading/prefiltered_env.h: 256 samples per texel, filtered importance sampling, level 1
// 128 x 64 texels halving down to 8 x 4); the irradiance polynomial of
// shading/irradiance_sh.h. Prefiltering and projection read the image box-filtered down to at
// most kSkyPrefilterWidth texels wide (finer than level 1 needs by four times).
struct SkyLighting {
    std::array<float, 3> poleTop{}, poleBottom{};  // of the image (EquirectView's poles)
    std::vector<EquirectImage> prefiltered;        // levels 1 .. kSkyLevels - 1
    ShIrradiance irradiance;

    // Level i as a view; level 0 needs the image the lighting was built from.
    EquirectView level(const SkyImage& image, int i) const;
};

// Builds the lighting of `image` on `threads` worker threads (0 = all); the result does not
// depend on the thread count.
SkyLighting buildSkyLighting(const SkyImage& image, int threads);

// The lighting of `image`, built on first use and then shared by every renderer, frame and
// thread for as long as the image lives (keyed by the shared pointer's owner, so a new image
// at an old address is never mistaken for the old one; entries of images that died are
// dropped at the next call). Thread-safe; `built`, when given, says whether this call built it.
std::shared_ptr<const SkyLighting> cachedSkyLighting(const std::shared_ptr<const SkyImage>& image,
                                                     int threads, bool* built = nullptr);

// How many images the cache holds lighting for (after dropping those that died); for tests.
int skyLightingCacheSize();

}  // namespace ssrt
