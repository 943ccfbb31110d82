// The OpenImageIO module (ssrt_oiio.so, io/oiio_module.h): the formats io/ does not decode
// itself, read through OpenImageIO as io/ always read them. Built as its own shared object
// so that only a process that needs it loads OpenImageIO's libraries.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <memory>

#include "io/image_limits.h"
#include "io/oiio_module.h"

namespace ssrt::io_detail {

namespace {

namespace OIIO = OIIO_NAMESPACE;

// PNG's alpha is straight; OpenImageIO associates it unless told otherwise. And OpenImageIO
// reads the format the name says, no other: by default a file its named reader refuses goes to
// every reader in turn (raw camera files, DICOM, video, ...), so that an embedded image glTF
// calls a PNG could be parsed by any of them, and each such refusal cost milliseconds and
// megabytes (LibRaw's set-up) before its one line. io/'s own decoders go by the bytes (PNG,
// JPEG, Radiance, EXR), so a misnamed file of those formats still reads.
OIIO::ImageSpec readConfig(AlphaMode alpha) {
    static const bool namedReaderOnly = OIIO::attribute("try_all_readers", 0);
    (void)namedReaderOnly;
    OIIO::ImageSpec config;
    if (alpha == AlphaMode::Straight) config.attribute("oiio:UnassociatedAlpha", 1);
    return config;
}

// Half samples as float. Read in their own type, not converted by read_image: OpenImageIO 2.4
// converts through a buffer of some 64 MB whatever the image's size (a 4 x 4 texture cost
// 6 ms and 16 k page faults). Half to float is exact, so the values are those read_image gave.
bool readHalf(OIIO::ImageInput& in, DecodedImage& out, std::string& error) {
    const OIIO::ImageSpec& spec = in.spec();
    Samples<uint16_t> half(out.sampleCount());
    if (!in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::HALF, half.data())) {
        error = in.geterror();
        return false;
    }
    out.type = SampleType::F32;
    out.f32.resize(out.sampleCount());
    const std::size_t row = std::size_t(out.width) * std::size_t(out.channels);
    for (std::size_t y = 0; y < std::size_t(out.height); ++y)
        OIIO::convert_pixel_values(OIIO::TypeDesc::HALF, half.data() + y * row,
                                   OIIO::TypeDesc::FLOAT, out.f32.data() + y * row, int(row));
    return true;
}

// Subimage 0, level 0, in the file's own 8- or 16-bit type, else as float.
bool readOpened(OIIO::ImageInput& in, DecodedImage& out, std::string& error) {
    const OIIO::ImageSpec& spec = in.spec();
    if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1) {
        error = "the image is empty";
        return false;
    }
    if (spec.depth > 1) {
        error = "volume images are not supported";
        return false;
    }
    if (const std::optional<std::string> problem =
            imageSizeProblem(spec.width, spec.height, spec.nchannels)) {
        error = *problem;
        return false;
    }
    out.width = spec.width;
    out.height = spec.height;
    out.channels = spec.nchannels;
    out.channelNames = spec.channelnames;
    out.srgb = OIIO::Strutil::iequals(spec.get_string_attribute("oiio:ColorSpace"), "sRGB");
    if (spec.channelformats.empty() && spec.format == OIIO::TypeDesc::HALF)
        return readHalf(in, out, error);
    bool ok = false;
    if (spec.format == OIIO::TypeDesc::UINT8) {
        out.type = SampleType::U8;
        out.u8.resize(out.sampleCount());
        ok = in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, out.u8.data());
    } else if (spec.format == OIIO::TypeDesc::UINT16) {
        out.type = SampleType::U16;
        out.u16.resize(out.sampleCount());
        ok = in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT16, out.u16.data());
    } else {
        out.type = SampleType::F32;
        out.f32.resize(out.sampleCount());
        ok = in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out.f32.data());
    }
    if (!ok) error = in.geterror();
    return ok;
}

bool decodeFile(const std::string& path, AlphaMode alpha, DecodedImage& out, std::string& error) {
    const OIIO::ImageSpec config = readConfig(alpha);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) {
        error = OIIO::geterror();
        return false;
    }
    return readOpened(*in, out, error);
}

bool decodeBytes(const void* bytes, std::size_t size, const std::string& formatHint,
                 AlphaMode alpha, DecodedImage& out, std::string& error) {
    OIIO::Filesystem::IOMemReader reader(bytes, size);
    // With a configuration, OIIO 2.4 takes the proxy from it, not from open()'s argument.
    OIIO::ImageSpec config = readConfig(alpha);
    OIIO::Filesystem::IOProxy* proxy = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    // OIIO picks the decoder by the extension of a file name ("x.png"; ".png" alone is read
    // as a name without one).
    const std::string ext = std::filesystem::path(formatHint).extension().string();
    auto in = OIIO::ImageInput::open("memory" + (ext.empty() ? formatHint : ext), &config, &reader);
    if (!in) {
        error = OIIO::geterror();
        return false;
    }
    return readOpened(*in, out, error);
}

constexpr OiioModule kModule{decodeFile, decodeBytes};

}  // namespace

}  // namespace ssrt::io_detail

extern "C" __attribute__((visibility("default"))) const ssrt::io_detail::OiioModule*
ssrt_oiio_module_v1() {
    return &ssrt::io_detail::kModule;
}
