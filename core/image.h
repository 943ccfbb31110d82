// Image planes: one channel each (structure of arrays), rows kRowElements elements apart
// (64 bytes for floats).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ssrt {

inline constexpr std::size_t kRowAlignment = 64;  // one cache line, one AVX-512 register
// A row's stride is a multiple of this many elements whatever the element type: 64 bytes of
// floats (and u32), 32 of u16, 16 of u8. So planes of one size have one stride in elements
// whatever their formats, and a kernel reading an f32 plane and an f16 one (the denoiser's
// guides and signals) addresses both pixels with one offset.
inline constexpr std::size_t kRowElements = kRowAlignment / sizeof(float);

// Tag for planes whose every pixel the caller writes next: only the row padding is zeroed,
// so no pass over the image (nor its page faults) is spent on a value about to be replaced.
struct Uninitialized {};
inline constexpr Uninitialized kUninitialized{};

template <class T>
class Plane {
public:
    Plane() = default;
    Plane(int width, int height, T fill = T{});
    Plane(int width, int height, Uninitialized);

    // Keeps the memory when the size is already right (contents then undefined but
    // finite: whatever the last frame left), else reallocates uninitialised.
    void ensureSize(int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }
    // Elements between the starts of two rows (>= width, a multiple of kRowElements).
    std::size_t stride() const { return stride_; }
    bool empty() const { return width_ == 0 || height_ == 0; }
    // What it holds, row padding included (0 when empty).
    std::size_t bytes() const { return stride_ * std::size_t(height_) * sizeof(T); }

    T* row(int y) { return data_.get() + std::size_t(y) * stride_; }
    const T* row(int y) const { return data_.get() + std::size_t(y) * stride_; }
    T& at(int x, int y) { return row(y)[x]; }
    const T& at(int x, int y) const { return row(y)[x]; }

    void fill(T value);
    Plane clone() const;

private:
    struct Free {
        void operator()(T* p) const;
    };
    // The bytes a plane of this size needs (a line more for elements narrower than 32 bits: a
    // 32-bit hardware gather of the last one reads past it, core/lanes.h gatherU16).
    static std::size_t blockBytes(std::size_t stride, int height);
    void zeroPadding();
    int width_ = 0, height_ = 0;
    std::size_t stride_ = 0;
    std::unique_ptr<T[], Free> data_;
};

using PlaneF = Plane<float>;
using PlaneU64 = Plane<uint64_t>;  // f16x4: four f16 channels a pixel (core/pixel_formats.h)
using PlaneU32 = Plane<uint32_t>;
using PlaneU16 = Plane<uint16_t>;  // f16 bits, u16, one channel of oct16 (core/pixel_formats.h)
using PlaneU8 = Plane<uint8_t>;    // unorm8, u8

// A float plane with a name ("viewZ", "normal.X", ...), as the renderer hands them out.
struct NamedPlane {
    std::string name;
    PlaneF plane;
};

// A borrowed plane with its layer name: what image files take (io/image_io.h).
struct LayerRef {
    std::string_view name;
    const PlaneF* plane = nullptr;
};

// Planes of one size with their names, as files hold them.
struct ImageLayers {
    int width = 0, height = 0;
    std::vector<LayerRef> layers;  // in file order
    // String attributes: an EXR's in the header (names must not be OpenEXR's own), e.g. what
    // part of a larger image a shard's file holds (cli/shard.h); a PNG's as tEXt chunks.
    std::vector<std::pair<std::string, std::string>> attributes = {};
};

// Pixels as an image file decodes them (io/), before the scene model takes them (a texture,
// a sky): interleaved float channels, row-major, row 0 first.
struct InterleavedImage {
    int width = 0, height = 0, channels = 0;
    std::vector<float> pixels;  // channels * width * height values
};

// FNV-1a over the visible pixels (padding excluded), for golden hashes.
uint64_t hashPlane(const PlaneF& plane, uint64_t seed = 0xcbf29ce484222325ull);
uint64_t hashPlane(const PlaneU64& plane, uint64_t seed = 0xcbf29ce484222325ull);
uint64_t hashPlane(const PlaneU32& plane, uint64_t seed = 0xcbf29ce484222325ull);
uint64_t hashPlane(const PlaneU16& plane, uint64_t seed = 0xcbf29ce484222325ull);
uint64_t hashPlane(const PlaneU8& plane, uint64_t seed = 0xcbf29ce484222325ull);

extern template class Plane<float>;
extern template class Plane<uint64_t>;
extern template class Plane<uint32_t>;
extern template class Plane<uint16_t>;
extern template class Plane<uint8_t>;

}  // namespace ssrt
