// Image files at the edge of the renderer: EXR with every named plane, PNG previews.
// OpenImageIO stays behind this header so the core library never sees it.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "io/write_options.h"
#include "renderer/frame.h"
#include "scenes/scene.h"

namespace ssrt {

// Writes a frame, the format chosen by the extension (case-insensitive):
//   .png  8-bit RGB from display.{R,G,B} (already tone mapped and sRGB encoded), each value
//         quantised as round(clamp(v, 0, 1) * 255); NaN becomes 0.
//   .exr  32-bit float, one channel per named plane of the groups options.layers names,
//         channel name = plane name ("color.R", "viewZ", ...), so viewers show "color",
//         "normal", ... as layers. Float, not half: ids and view depth need every bit. Written
//         by OpenEXR with options.compression (lossless) on options.threads threads; the
//         bytes do not depend on the thread count or on when the file is written.
// The file appears whole or not at all: it is written to a temporary beside the target and
// renamed over it only on success. Throws std::invalid_argument for an unsupported extension
// or a frame without the planes the format needs, std::runtime_error (one line, naming the
// path and the reason) when the file cannot be written. An EXR whose chosen groups hold no
// plane is refused (std::invalid_argument).
// The frame's layers (Frame::layers()).
void writeImage(const std::string& path, const Frame& frame, const WriteOptions& options = {});

// Planes of one size with their names, as files hold them.
struct ImageLayers {
    int width = 0, height = 0;
    std::vector<PlaneRef> layers;  // in file order
    // EXR only (a PNG has none): string attributes in the header, e.g. what part of a larger
    // image a shard's file holds (cli/shard.h). Names must not be OpenEXR's own.
    std::vector<std::pair<std::string, std::string>> attributes = {};
};
void writeImage(const std::string& path, const ImageLayers& image,
                const WriteOptions& options = {});

// Fails fast, before minutes of rendering, for a path writeImage would reject: throws
// std::invalid_argument for an unsupported extension and std::runtime_error when the
// directory is missing, is not a directory, or is not writable, or the path is a directory.
// Creates and removes a probe file, so nothing is left behind.
void checkWritable(const std::string& path);

// Whether writeImage writes `path` as an EXR (its extension, case-insensitive, is .exr):
// the files --layers and the compression apply to.
bool isExrPath(const std::string& path);
// Whether its extension, case-insensitive, is .png (an 8-bit preview, or ssrt diff's heat map).
bool isPngPath(const std::string& path);

// Extensions writeImage accepts, with the dot: ".png", ".exr".
const std::vector<std::string>& supportedImageExtensions();

// An equirectangular environment image for Sky::Kind::Image, from any file OpenImageIO reads
// (.exr, .hdr, ...; subimage 0, level 0). Channels: R, G, B by name when present, else the
// first three; one channel (or two: grey and alpha) is grey. Values are linear; a file
// tagged sRGB (8-bit PNG, JPEG) is decoded to linear. Negative values become 0; an image
// larger than 2^24 texels (above 8192 x 2048) is box-filtered to half size until it fits (the
// renderer's float texel indices). Throws std::runtime_error, one line naming the path, if
// the file cannot be read or holds a NaN or an infinity.
SkyImage readSkyImage(const std::string& path);

// The string attributes of an EXR file's header (ImageLayers::attributes and OpenEXR's own
// string attributes), by name. Throws std::runtime_error naming the path if it cannot be read.
std::map<std::string, std::string> readExrStringAttributes(const std::string& path);

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
