#include "io/jpeg_io.h"

// jpeglib.h needs size_t and FILE declared before it.
#include <cstdio>
// clang-format off
#include <jpeglib.h>
#include <jerror.h>
// clang-format on
#include <csetjmp>
#include <vector>

#include "io/io_errors.h"

namespace ssrt::io_detail {

namespace {

// libjpeg's error manager with the place to jump back to and the message.
struct JpegErrors {
    jpeg_error_mgr manager;
    std::jmp_buf jump;
    char text[JMSG_LENGTH_MAX];
};

[[noreturn]] void onJpegError(j_common_ptr info) {
    auto* errors = reinterpret_cast<JpegErrors*>(info->err);
    info->err->format_message(info, errors->text);
    std::longjmp(errors->jump, 1);
}

// Warnings about damaged data (a bad marker, a corrupt Huffman code) do not stop OpenImageIO's
// decoding, so they do not stop ours; trace messages are dropped. A file cut short does stop
// it: libjpeg would fill the missing rows with grey (OpenImageIO gives that image and a
// warning), and a renderer given a damaged file should say so, not draw grey. It also keeps a
// few bytes claiming 16384 x 8192 pixels from decoding all of them: the rows after the cut
// are never touched.
void onJpegMessage(j_common_ptr info, int level) {
    // JWRN_JPEG_EOF: the file ends; JWRN_HIT_MARKER: a scan's data ends (at the next marker,
    // an end of image after a cut, say) before its pixels.
    const int code = info->err->msg_code;
    if (level < 0 && (code == JWRN_JPEG_EOF || code == JWRN_HIT_MARKER)) {
        auto* errors = reinterpret_cast<JpegErrors*>(info->err);
        std::snprintf(errors->text, sizeof errors->text,
                      "the file is cut short (its data ends before its %u x %u pixels)",
                      unsigned(reinterpret_cast<j_decompress_ptr>(info)->image_width),
                      unsigned(reinterpret_cast<j_decompress_ptr>(info)->image_height));
        std::longjmp(errors->jump, 1);
    }
}

// Owns libjpeg's decompressor; set up with the errors above before anything can fail.
struct JpegRead {
    jpeg_decompress_struct info{};
    JpegErrors errors{};
    bool created = false;
    ~JpegRead() {
        if (created) jpeg_destroy_decompress(&info);
    }
};

// The header. Returns 0 on success, 1 after an error, 2 for a CMYK or YCCK file.
int readHeader(JpegRead& r, const uint8_t* bytes, std::size_t size) {
    if (setjmp(r.errors.jump)) return 1;
    jpeg_create_decompress(&r.info);
    r.created = true;
    jpeg_mem_src(&r.info, bytes, static_cast<unsigned long>(size));
    jpeg_read_header(&r.info, TRUE);
    if (r.info.jpeg_color_space == JCS_CMYK || r.info.jpeg_color_space == JCS_YCCK) return 2;
    return 0;
}

// The decompressor started with libjpeg's defaults (OpenImageIO's); false after an error.
bool start(JpegRead& r) {
    if (setjmp(r.errors.jump)) return false;
    jpeg_start_decompress(&r.info);
    return true;
}

bool readRows(JpegRead& r, uint8_t* pixels, std::size_t rowBytes) {
    if (setjmp(r.errors.jump)) return false;
    while (r.info.output_scanline < r.info.output_height) {
        JSAMPROW row = pixels + std::size_t(r.info.output_scanline) * rowBytes;
        jpeg_read_scanlines(&r.info, &row, 1);
    }
    return true;
}

}  // namespace

bool isJpeg(const uint8_t* bytes, std::size_t size) {
    return size >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff;
}

std::optional<DecodedImage> decodeJpeg(const uint8_t* bytes, std::size_t size) {
    JpegRead r;
    r.info.err = jpeg_std_error(&r.errors.manager);
    r.errors.manager.error_exit = onJpegError;
    r.errors.manager.emit_message = onJpegMessage;
    const int header = readHeader(r, bytes, size);
    if (header == 1) failDecode(r.errors.text);
    if (header == 2) return std::nullopt;
    // Before the decompressor allocates its buffers for a width the header may invent.
    checkImageSize(r.info.image_width, r.info.image_height, r.info.num_components);
    if (!start(r)) failDecode(r.errors.text);
    DecodedImage image;
    image.width = int(r.info.output_width);
    image.height = int(r.info.output_height);
    image.channels = r.info.output_components;
    image.channelNames = defaultChannelNames(image.channels);
    image.type = SampleType::U8;
    image.srgb = true;  // OpenImageIO's assumption for every JPEG
    image.u8.resize(image.sampleCount());
    if (!readRows(r, image.u8.data(), std::size_t(image.width) * image.channels))
        failDecode(r.errors.text);
    return image;
}

}  // namespace ssrt::io_detail
