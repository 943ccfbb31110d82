#include "io/exr_imf_pixels.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "io/io_errors.h"

namespace ssrt::io_detail {

namespace {

// Bytes in memory as InputFile reads a file.
class MemoryStream : public Imf::IStream {
public:
    MemoryStream(const uint8_t* bytes, std::size_t size)
        : Imf::IStream("memory.exr"), bytes_(bytes), size_(size) {}
    bool read(char c[], int n) override {
        if (n < 0 || std::size_t(n) > size_ - std::min(at_, size_))
            throw std::runtime_error("the data end before the file does");
        std::memcpy(c, bytes_ + at_, std::size_t(n));
        at_ += std::size_t(n);
        return at_ < size_;
    }
    uint64_t tellg() override { return at_; }
    void seekg(uint64_t at) override { at_ = std::size_t(std::min<uint64_t>(at, size_)); }

private:
    const uint8_t* bytes_;
    std::size_t size_, at_ = 0;
};

// Whether InputFile's reading of the header is the core library's, in all that sizes a buffer.
bool sameHeader(const Imf::Header& header, const ExrHeaderFacts& facts) {
    const Imath::Box2i window = header.dataWindow();
    if (window.min.x != facts.minX || window.min.y != facts.minY || window.max.x != facts.maxX ||
        window.max.y != facts.maxY || int(header.compression()) != facts.compression ||
        header.hasTileDescription() != facts.tiled)
        return false;
    std::size_t i = 0;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it, ++i)
        if (i >= facts.channelNames.size() || it.name() != facts.channelNames[i] ||
            int(it.channel().type) != facts.channelTypes[i] || it.channel().xSampling != 1 ||
            it.channel().ySampling != 1)
            return false;
    return i == facts.channelNames.size();
}

}  // namespace

void readPixelsWithInputFile(const std::string& name, const uint8_t* bytes, std::size_t size,
                             const ExrHeaderFacts& facts, const std::vector<int>& outputOf,
                             DecodedImage& image) {
    try {
        std::unique_ptr<MemoryStream> stream;
        if (bytes) stream = std::make_unique<MemoryStream>(bytes, size);
        std::unique_ptr<Imf::InputFile> file = stream
                                                   ? std::make_unique<Imf::InputFile>(*stream)
                                                   : std::make_unique<Imf::InputFile>(name.c_str());
        if (!sameHeader(file->header(), facts))
            failDecode("the header is damaged: OpenEXR reads it two ways");
        const Imath::Box2i window = file->header().dataWindow();
        const std::size_t pixelBytes = sizeof(float) * std::size_t(image.channels);
        Imf::FrameBuffer buffer;
        for (std::size_t i = 0; i < facts.channelNames.size(); ++i) {
            // The window's first pixel; Slice::Make offsets it by the window's origin.
            char* first = reinterpret_cast<char*>(image.f32.data() + outputOf[i]);
            const Imf::PixelType type =
                facts.channelTypes[i] == int(Imf::UINT) ? Imf::UINT : Imf::FLOAT;
            buffer.insert(facts.channelNames[i],
                          Imf::Slice::Make(type, first, window, pixelBytes,
                                           pixelBytes * std::size_t(image.width)));
        }
        file->setFrameBuffer(buffer);
        file->readPixels(window.min.y, window.max.y);
    } catch (const DecodeFailure&) {
        throw;
    } catch (const std::exception& e) {
        failDecode(e.what());
    }
}

}  // namespace ssrt::io_detail
