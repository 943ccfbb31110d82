// libFuzzer target for environment images (io/image_io.h readSkyImage): Radiance HDR, EXR, PNG
// and JPEG through io/'s own decoders, anything else through OpenImageIO. Every input either
// gives an image or is refused with std::runtime_error (one line naming the file); anything
// else (a crash, a sanitizer report, std::bad_alloc, another exception) is a bug.
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz_files.h"
#include "io/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    // The extension only matters for what goes to OpenImageIO (the decoders go by the bytes).
    static const char* const kExtensions[] = {".hdr", ".exr", ".png", ".jpg"};
    const std::string name = "sky" + std::string(kExtensions[size > 0 ? data[size - 1] % 4 : 0]);
    const std::string path =
        ssrt::fuzz::writeFile(name, {reinterpret_cast<const char*>(data), size});
    try {
        const ssrt::InterleavedImage image = ssrt::readSkyImage(path);
        if (image.channels != 3 ||
            image.pixels.size() != std::size_t(image.width) * std::size_t(image.height) * 3)
            std::abort();  // readSkyImage's contract: RGB, every pixel
    } catch (const std::runtime_error&) {
        // refused cleanly: fine
    }
    return 0;
}
