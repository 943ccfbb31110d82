// What a pass reads from the frame, as views made from the frame graph's declarations
// (renderer/frame_graph_decl.cpp): the one place where the renderer chooses and checks a
// pass's inputs. A resource the pass declares reading under the graph's settings comes back as
// views of its planes, each checked made and of the frame's size; one it does not declare
// comes back absent, so a kernel that reads what its pass does not declare finds it missing
// (its module's argument check names it) instead of reading a plane the frame's memory may
// have given to another resource. No pass repeats the settings that decide what it reads.
//
// It sees the planes the passes hand each other through the Frame (its image and outputs, its
// G-buffer, the direct pass's parts) and the last frame's (FrameHistory). The buffers a pass
// makes for the next in Frame::Scratch (the shadow map, the pyramids, the half frame, the
// batches) are handed over as objects that their readers check; the denoiser's scratch and
// history are its own (denoise/denoise.h).
#pragma once

#include <string_view>
#include <vector>

#include "core/gbuffer_view.h"
#include "core/plane_view.h"
#include "renderer/frame.h"
#include "renderer/frame_graph.h"

namespace ssrt {

class PassReads {
public:
    // The reads the compiled graph keeps for `pass` (std::logic_error when the graph does not
    // run it), over `frame` and the last frame's `history` (optional). Checks at once every
    // plane of a declared read that the frame or the history holds: made, and of the frame's
    // size; else std::logic_error naming the pass and the channel.
    PassReads(const CompiledGraph& graph, const Frame& frame, std::string_view pass,
              const FrameHistory* history = nullptr);

    // Whether the pass reads `id` under the graph's settings.
    bool has(Res id) const;
    // Channel `channel` of `id`, f32 or f16; absent where the pass does not read it.
    FloatView value(Res id, int channel = 0) const;
    // The same of an f32 plane (std::logic_error for an f16 one).
    ViewF view(Res id, int channel = 0) const;
    // The frame's visibility ids (Res::VisibilityIds, raster/raster.h), checked as the planes
    // above; absent where the pass does not read them.
    ViewU32 ids(Res id) const;
    // The frame's G-buffer holding the planes the pass declares reading, the rest absent.
    GBufferView gbuffer() const;

private:
    struct Plane {
        Res id;
        int channel;
        const PlaneF* f32;
        const PlaneU16* f16;
    };
    const Plane* find(Res id, int channel) const;

    std::string_view pass_;
    const GraphPass* decl_ = nullptr;
    const Frame& frame_;
    std::vector<Plane> planes_;      // of the declared reads the frame and the history hold
    const PlaneU32* ids_ = nullptr;  // the visibility ids, where declared
};

}  // namespace ssrt
