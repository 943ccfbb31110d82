// libFuzzer target for `ssrt diff A B`: the input is the two images (split by fuzz_files.h's
// marker), each EXR, PNG, HDR or JPEG by its own bytes, compared with FLIP when the first byte
// says so. Every input must end in a status of ssrt's with one error line or a table.
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const std::vector<std::string_view> pieces = ssrt::fuzz::splitInput(data + 1, size - 1);
    if (pieces.size() != 2) return 0;
    // The extension only matters for what goes to OpenImageIO (the decoders go by the bytes).
    static const char* const kExtensions[] = {".exr", ".png", ".hdr", ".jpg"};
    std::vector<std::string> args = {
        "diff", ssrt::fuzz::writeFile(std::string("a") + kExtensions[data[0] % 4], pieces[0]),
        ssrt::fuzz::writeFile(std::string("b") + kExtensions[(data[0] >> 2) % 4], pieces[1])};
    if (data[0] & 16) args.push_back("--flip");
    ssrt::fuzz::runSsrt(args);
    return 0;
}
