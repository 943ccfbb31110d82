// Image files at the edge of the renderer: EXR with every named plane, PNG previews, sky
// images and channels read back. The libraries (libpng, libjpeg, stb_image, OpenEXR, and
// OpenImageIO in a module loaded on first need: io/image_decode.h) stay behind this header.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"
#include "io/write_options.h"

namespace ssrt {

// Writes named layers (core/image.h; a frame's come from renderer/layer_groups.h, which
// chooses them), the format chosen by the extension (case-insensitive):
//   .png  8-bit RGB from display.{R,G,B} (already tone mapped and sRGB encoded), each value
//         quantised as round(clamp(v, 0, 1) * 255); NaN becomes 0. Other layers are ignored.
//         Deflated by zlib at level 1 (Up filter, run-length strategy) in fixed bands of
//         rows compressed side by side: the same bytes on any thread count (io/png_io.h).
//   .exr  32-bit float, one channel per layer, in the order given, channel name = layer name
//         ("color.R", "viewZ", ...), so viewers show "color", "normal", ... as layers; with a
//         colour layer (color.R, .G, .B, else a reference's ref.color.R, .G, .B) and no R, G
//         or B of its own, that layer again as the default channels R, G, B, which viewers and
//         `oiiotool --stats` show by default.
//         Float, not half: ids and view depth need every bit. Written by OpenEXR with
//         options.compression (lossless) on options.threads threads; the bytes do not depend
//         on the thread count or on when the file is written.
// The file appears whole or not at all: it is written to a temporary beside the target and
// renamed over it only on success. Throws std::invalid_argument for an unsupported extension
// or an image without the planes the format needs (an empty list of layers included),
// std::runtime_error (one line, naming the path and the reason) when the file cannot be
// written.
void writeImage(const std::string& path, const ImageLayers& image,
                const WriteOptions& options = {});

// Writes `text` to `path` whole or not at all, as writeImage writes an image (a temporary
// beside it, renamed over it): the CSVs, reports and other text files. Throws
// std::runtime_error, one line naming the path and the reason ("No space left on device").
void writeTextWhole(const std::string& path, const std::string& text);

// Removes the temporaries of the writes in flight in this process (writeImage's,
// writeTextWhole's, checkWritable's probe), for a signal handler about to end the process
// (cli/interrupt.h): async-signal-safe, it only reads fixed buffers and calls unlink().
void removeTemporariesInFlight() noexcept;

// Fails fast, before minutes of rendering, for a path writeImage would reject: throws
// std::invalid_argument for an unsupported extension and std::runtime_error when the
// directory is missing, is not a directory, or is not writable, or the path is a directory.
// Creates and removes a probe file, so nothing is left behind.
void checkWritable(const std::string& path);

// For a heat map's path, before any work: a .png (else std::invalid_argument calling it
// `what`) that checkWritable accepts.
void checkPngOutput(const std::string& path, const std::string& what);
// Writes three planes of display values (as they are, no tone map) as a PNG.
void writeDisplayPng(const std::string& path, const PlaneF& r, const PlaneF& g, const PlaneF& b);

// Whether writeImage writes `path` as an EXR (its extension, case-insensitive, is .exr):
// the files the layer choice and the compression apply to.
bool isExrPath(const std::string& path);
// Whether its extension, case-insensitive, is .png (an 8-bit preview, or ssrt diff's heat map).
bool isPngPath(const std::string& path);

// Extensions writeImage accepts, with the dot: ".png", ".exr".
const std::vector<std::string>& supportedImageExtensions();

// An equirectangular environment image (for Sky::Kind::Image: renderer/sky_lighting.h
// makeSkyImage takes it) as RGB (3 channels), from any image file io/ reads (.exr, .hdr,
// .png, .jpg, or any other OpenImageIO reads; subimage 0, level 0; an alpha channel is
// associated, as OpenImageIO did). Channels: R, G, B by name when present, else the first three;
// one channel (or two: grey and alpha) is grey. Values are linear; a file tagged sRGB (8-bit
// PNG, JPEG) is decoded to linear. Negative values become 0. Throws std::runtime_error, one
// line naming the path, if the file cannot be read or holds a NaN or an infinity.
InterleavedImage readSkyImage(const std::string& path);

// The string attributes of an EXR file's header (ImageLayers::attributes and OpenEXR's own
// string attributes), by name. Throws std::runtime_error naming the path if it cannot be read.
std::map<std::string, std::string> readExrStringAttributes(const std::string& path);

// An EXR's string attributes (readExrStringAttributes) or a PNG's tEXt chunks, by name.
// Throws std::runtime_error naming the path for another format or a file that cannot be read.
std::map<std::string, std::string> readImageAttributes(const std::string& path);

// Writes the image file `from` again as `to` (both .exr or both .png), every channel's values
// kept, with `attributes` added: an EXR's channels as they are (32-bit float, ZIP-compressed),
// a PNG's R, G, B as its 8 bits. Whole or not at all, as writeImage. Throws as readChannels and
// writeImage do.
void copyImageWithAttributes(const std::string& from, const std::string& to,
                             const std::vector<std::pair<std::string, std::string>>& attributes);

// Channel names of an image file in the order the reader reports them (OpenEXR stores
// channels sorted by name, so this need not be the order they were written in).
std::vector<std::string> readChannelNames(const std::string& path);

// One channel of an image file as floats, row by row without padding; sets width and height.
// Throws std::runtime_error naming the path if the file or the channel cannot be read.
std::vector<float> readChannel(const std::string& path, const std::string& channel, int& width,
                               int& height);

// Several channels of one file, read and decompressed once (readChannel per channel would
// decode the whole file each time): result[i] is channels[i], row by row without padding.
// Throws as readChannel does.
std::vector<std::vector<float>> readChannels(const std::string& path,
                                             const std::vector<std::string>& channels, int& width,
                                             int& height);

}  // namespace ssrt
