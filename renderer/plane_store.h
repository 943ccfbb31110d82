// f32 planes held by resource: one plane per channel of each resource a store is made for, in
// the resource table's order (renderer/resources.cpp). So a resource is one line of that table,
// and no struct lists it again with a member and a name per plane. The frame's outputs are one
// store (its image, what SSR and SSGI hand out, the denoiser's), the half frame's denoised
// diffuse another, the truth's per-ray checks a third. A resource a store holds but that was
// not made this time has empty planes (and is no layer).
#pragma once

#include <array>
#include <span>
#include <string_view>
#include <vector>

#include "core/image.h"
#include "core/plane_view.h"
#include "renderer/resources.h"

namespace ssrt {

class PlaneStore {
public:
    // A store of `ids` (each f32: std::logic_error for another format).
    explicit PlaneStore(std::span<const Res> ids);
    PlaneStore(std::initializer_list<Res> ids)
        : PlaneStore(std::span<const Res>(ids.begin(), ids.size())) {}
    // The frame's outputs: every output outside the G-buffer, in the table's order.
    static PlaneStore frameOutputs();

    // Whether the store holds `id`.
    bool holds(Res id) const { return !planes_[std::size_t(id)].empty(); }

    // A resource's planes, one per channel (std::logic_error for one the store does not hold).
    PlaneF* planes(Res id);
    const PlaneF* planes(Res id) const;
    // The three planes of an RGB resource (std::logic_error for another).
    std::span<PlaneF, 3> rgb(Res id);
    std::span<const PlaneF, 3> rgb(Res id) const;
    // Channel `channel` of a resource (std::logic_error past its channels).
    PlaneF& plane(Res id, int channel = 0);
    const PlaneF& plane(Res id, int channel = 0) const;

    // A channel as a pass reads it, and as a pass writes it (sized first), named by the table.
    ViewF view(Res id, int channel = 0) const {
        return viewOf(plane(id, channel), channelName(id, channel));
    }
    OutF output(Res id, int channel, int width, int height) {
        PlaneF& p = plane(id, channel);
        p.ensureSize(width, height);
        return outputOf(p, channelName(id, channel));
    }

    // fn(channel name, plane) for every plane of the store's resources of `group` (outputs), or
    // of all of them, in the table's order.
    template <class Fn>
    void forEachPlane(LayerGroup group, Fn&& fn) {
        forEachOf(*this, &group, fn);
    }
    template <class Fn>
    void forEachPlane(LayerGroup group, Fn&& fn) const {
        forEachOf(*this, &group, fn);
    }
    template <class Fn>
    void forEachPlane(Fn&& fn) {
        forEachOf(*this, nullptr, fn);
    }
    template <class Fn>
    void forEachPlane(Fn&& fn) const {
        forEachOf(*this, nullptr, fn);
    }
    // fn(channel name, plane) for each channel of one resource.
    template <class Fn>
    void forEachChannelOf(Res id, Fn&& fn) const {
        const PlaneF* p = planes(id);
        for (int i = 0; i < resourceDecl(id).channelCount(); ++i) fn(channelName(id, i), p[i]);
    }

private:
    template <class S, class Fn>
    static void forEachOf(S& s, const LayerGroup* group, Fn& fn) {
        for (int r = 0; r < kResourceCount; ++r) {
            auto& planes = s.planes_[std::size_t(r)];
            if (planes.empty() || (group && resourceDecl(Res(r)).group != *group)) continue;
            for (std::size_t i = 0; i < planes.size(); ++i)
                fn(channelName(Res(r), int(i)), planes[i]);
        }
    }

    std::array<std::vector<PlaneF>, kResourceCount> planes_;
};

}  // namespace ssrt
