// Radiance RGBE (.hdr) through stb_image (Debian's libstb-dev; inside io/ only).
//
// Why stb_image: one header, in Debian, fuzzed and used widely, and its RGBE decoding is the
// same arithmetic as OpenImageIO 2.4's (mantissa times 2^(exponent - 136), 0 for exponent 0:
// exact in float), so the texels are the same bits. Only its HDR decoder is compiled
// (STBI_ONLY_HDR), about 300 lines. It reads the usual orientation (-Y +X); a file it
// refuses goes to OpenImageIO, which reads the other orientations or gives its error. The size
// a header claims, in any orientation, is checked here first, for both.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include "io/decoded_image.h"

namespace ssrt::io_detail {

// Whether the bytes start with a Radiance header's "#?".
bool isRadianceHdr(const uint8_t* bytes, std::size_t size);

// DecodeFailure when the bytes hold a Radiance resolution line (after a header's blank line, in
// any orientation) whose size is over the limits or that the bytes are too short for; called
// by decodeRadianceHdr, and for bytes OpenImageIO reads as Radiance by their name (its reader
// takes headers without "#?").
void checkRadianceClaim(const uint8_t* bytes, std::size_t size);

// R, G, B float, linear; empty when stb_image refuses the file. DecodeFailure when the header's
// size is over the limits or the file too short for it.
std::optional<DecodedImage> decodeRadianceHdr(const uint8_t* bytes, std::size_t size);

}  // namespace ssrt::io_detail
