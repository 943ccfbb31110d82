#include "renderer/pass_reads.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace ssrt {

PassReads::PassReads(const CompiledGraph& graph, const Frame& frame, std::string_view pass,
                     const FrameHistory* history)
    : pass_(pass), frame_(frame) {
    const auto p = std::find_if(graph.passes.begin(), graph.passes.end(),
                                [&](const GraphPass& g) { return g.decl->name == pass; });
    if (p == graph.passes.end())
        throw std::logic_error("pass reads: the frame graph does not run '" + std::string(pass) +
                               "'");
    decl_ = &*p;
    const std::string who = "pass '" + std::string(pass) + "' reads '";
    const auto add = [&](std::string_view name, const auto& plane) {
        const Res id = resourceOfChannel(name);
        if (!has(id)) return;
        if (plane.empty()) throw std::logic_error(who + std::string(name) + "', which is missing");
        if (plane.width() != graph.width || plane.height() != graph.height)
            throw std::logic_error(
                who + std::string(name) + "', which is " + std::to_string(plane.width()) + "x" +
                std::to_string(plane.height()) + ", not " + std::to_string(graph.width) + "x" +
                std::to_string(graph.height));
        const int channel = int(std::count_if(planes_.begin(), planes_.end(),
                                              [&](const Plane& q) { return q.id == id; }));
        if constexpr (std::is_same_v<std::decay_t<decltype(plane)>, PlaneU32>) ids_ = &plane;
        else if constexpr (std::is_same_v<std::decay_t<decltype(plane)>, PlaneU16>)
            planes_.push_back({id, channel, nullptr, &plane});
        else planes_.push_back({id, channel, &plane, nullptr});
    };
    frame.forEachPlane(add);
    add(channelName(Res::VisibilityIds, 0), frame.scratch.visibility.ids);
    if (history) history->forEachPlane(add);
}

bool PassReads::has(Res id) const {
    return std::any_of(decl_->reads.begin(), decl_->reads.end(),
                       [&](const Access& a) { return a.res == id; });
}

const PassReads::Plane* PassReads::find(Res id, int channel) const {
    if (!has(id)) return nullptr;
    for (const Plane& p : planes_)
        if (p.id == id && p.channel == channel) return &p;
    throw std::logic_error("pass '" + std::string(pass_) + "' reads '" +
                           std::string(channelName(id, channel)) +
                           "', which neither the frame nor its history holds");
}

FloatView PassReads::value(Res id, int channel) const {
    const Plane* p = find(id, channel);
    if (!p) return ViewF{nullptr, 0, 0, 0, channelName(id, channel)};
    if (p->f16) return viewOf(*p->f16, channelName(id, channel));
    return viewOf(*p->f32, channelName(id, channel));
}

ViewF PassReads::view(Res id, int channel) const {
    const Plane* p = find(id, channel);
    if (!p) return {nullptr, 0, 0, 0, channelName(id, channel)};
    if (!p->f32)
        throw std::logic_error("pass '" + std::string(pass_) + "' reads '" +
                               std::string(channelName(id, channel)) + "' as f32; it is f16");
    return viewOf(*p->f32, channelName(id, channel));
}

ViewU32 PassReads::ids(Res id) const {
    const std::string_view name = channelName(id, 0);  // (the resource table's: it outlives us)
    if (!has(id)) return {nullptr, 0, 0, 0, name};
    if (id != Res::VisibilityIds || !ids_)
        throw std::logic_error("pass '" + std::string(pass_) + "' reads '" + std::string(name) +
                               "' as ids; it is not the visibility buffer's");
    return viewOf(*ids_, name);
}

GBufferView PassReads::gbuffer() const {
    GBufferPlanes mask = 0;
    for (const Access& a : decl_->reads)
        if (resourceDecl(a.res).group == LayerGroup::GBuffer) mask |= resourceDecl(a.res).gbuffer;
    const GBufferView all = frame_.gbuffer.view();
    GBufferView only;
    only.width = all.width;
    only.height = all.height;
    only.stride = all.stride;
    return withPlanes(only, all, mask);
}

}  // namespace ssrt
