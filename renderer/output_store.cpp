#include "renderer/output_store.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace ssrt {

bool OutputStore::holds(Res id) {
    const ResourceDecl& d = resourceDecl(id);
    if (d.lifetime != Lifetime::Output || d.group == LayerGroup::GBuffer) return false;
    // (The denoiser writes into planes of its own: denoise/denoise.h, DenoiseOutputs.)
    return !(id == Res::DenoisedDiffuse || id == Res::DenoisedSpecular ||
             id == Res::DiffuseFrames || id == Res::SpecularFrames);
}

OutputStore::OutputStore() {
    for (int r = 0; r < kResourceCount; ++r)
        if (holds(Res(r)))
            planes_[std::size_t(r)].resize(std::size_t(resourceDecl(Res(r)).channelCount()));
}

PlaneF* OutputStore::planes(Res id) { return const_cast<PlaneF*>(std::as_const(*this).planes(id)); }

const PlaneF* OutputStore::planes(Res id) const {
    if (!holds(id))
        throw std::logic_error("the frame's outputs hold no '" +
                               std::string(resourceDecl(id).name) + "'");
    return planes_[std::size_t(id)].data();
}

std::span<PlaneF, 3> OutputStore::rgb(Res id) {
    checkChannelCount(id, 3);
    return std::span<PlaneF, 3>(planes(id), 3);
}

std::span<const PlaneF, 3> OutputStore::rgb(Res id) const {
    checkChannelCount(id, 3);
    return std::span<const PlaneF, 3>(planes(id), 3);
}

PlaneF& OutputStore::plane(Res id, int channel) {
    return const_cast<PlaneF&>(std::as_const(*this).plane(id, channel));
}

const PlaneF& OutputStore::plane(Res id, int channel) const {
    const PlaneF* p = planes(id);
    if (channel < 0 || channel >= resourceDecl(id).channelCount())
        throw std::logic_error("resource '" + std::string(resourceDecl(id).name) +
                               "' has no channel " + std::to_string(channel));
    return p[channel];
}

}  // namespace ssrt
