#include "renderer/plane_store.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace ssrt {

PlaneStore::PlaneStore(std::span<const Res> ids) {
    for (Res id : ids) {
        const ResourceDecl& d = resourceDecl(id);
        if (d.format != PixelFormat::F32)
            throw std::logic_error("a plane store holds f32 planes, not '" + std::string(d.name) +
                                   "'");
        planes_[std::size_t(id)].resize(std::size_t(d.channelCount()));
    }
}

PlaneStore PlaneStore::frameOutputs() {
    std::vector<Res> ids;
    for (int r = 0; r < kResourceCount; ++r) {
        const ResourceDecl& d = resourceDecl(Res(r));
        if (d.lifetime == Lifetime::Output && d.group != LayerGroup::GBuffer) ids.push_back(Res(r));
    }
    return PlaneStore(ids);
}

PlaneF* PlaneStore::planes(Res id) { return const_cast<PlaneF*>(std::as_const(*this).planes(id)); }

const PlaneF* PlaneStore::planes(Res id) const {
    if (!holds(id))
        throw std::logic_error("no plane store here holds '" + std::string(resourceDecl(id).name) +
                               "'");
    return planes_[std::size_t(id)].data();
}

std::span<PlaneF, 3> PlaneStore::rgb(Res id) {
    checkChannelCount(id, 3);
    return std::span<PlaneF, 3>(planes(id), 3);
}

std::span<const PlaneF, 3> PlaneStore::rgb(Res id) const {
    checkChannelCount(id, 3);
    return std::span<const PlaneF, 3>(planes(id), 3);
}

PlaneF& PlaneStore::plane(Res id, int channel) {
    return const_cast<PlaneF&>(std::as_const(*this).plane(id, channel));
}

const PlaneF& PlaneStore::plane(Res id, int channel) const {
    const PlaneF* p = planes(id);
    if (channel < 0 || channel >= resourceDecl(id).channelCount())
        throw std::logic_error("resource '" + std::string(resourceDecl(id).name) +
                               "' has no channel " + std::to_string(channel));
    return p[channel];
}

}  // namespace ssrt
