// The frame's memory as the graph says (renderer/frame_graph.h): the planes of the Frame's own
// groups (image, G-buffer, material, ids, direct parts, traced signals, denoised) are taken
// from the frame's pool just before the first pass that writes them, and a transient one goes
// back to the pool just after the last pass that reads it, where a later pass's planes take
// its memory. So the resources with disjoint lifetimes share memory at run time as the graph's
// placement shares it on paper (CompiledGraph::transientBytes), and an output nothing asked
// for (a PNG's G-buffer) is gone once read. The scratch's own buffers of a transient (the shadow
// map, the visibility buffers, the back-face layer, the Hi-Z levels) are freed after its last pass:
// their memory goes back to the planes' range (core/plane_memory.h), where later planes of any size
// take it; its pages stay resident, so a frame rendered again faults none in. (Filament's
// FrameGraph realises its virtual resources before their first pass and destroys them after their
// last, so.)
//
// The renderer runs its passes in steps (each chain and whole pass of the frame scheduler,
// renderer/frame_scheduler.h; the history's commit): each step() covers the declared passes after
// the last step's, through the one it names, in declaration order, so a step holds whatever pass of
// it the settings keep.
#pragma once

#include <string_view>
#include <vector>

#include "renderer/frame.h"
#include "renderer/frame_graph.h"

namespace ssrt {

class FrameMemory {
public:
    // Every plane of the frame's groups goes back to the pool (a Frame rendered into again
    // keeps its memory there), the pool keeps only planes of this frame's sizes. `forTruth`:
    // the direct pass's parts (Frame::direct) and the scratch's buffers stay to the frame's
    // end, as the truth and the tests read them after it (truth/parts.h: the parts;
    // truth/reference_image.h: the shadow map; the back-face layer); RenderSettings::
    // tracePlanes says so.
    FrameMemory(const CompiledGraph& graph, Frame& frame, bool forTruth);

    // Runs `fn` as the passes through `last`: takes the planes they write first before it,
    // gives back the transients they read last after it.
    template <class Fn>
    void step(std::string_view last, Fn&& fn) {
        const int end = declIndex(last);
        take(end);
        fn();
        give(end);
        done_ = end;
    }
    // Within a step: the transients whose last pass is at or before `pass` go back now (the
    // denoiser's front end has read the traced signals).
    void giveThrough(std::string_view pass) { give(declIndex(pass)); }

private:
    struct Held {
        Res id;
        int first, last;  // declaration indices of its first and last pass
        bool transient;
        // Its planes in the Frame's groups, in channel order; none for a resource in
        // Frame::Scratch's own buffers, which are freed, not pooled, after its last pass.
        // (A resource's planes are of one format: f32 or f16.)
        std::vector<PlaneF*> planes;
        std::vector<PlaneU16*> planesU16;
        bool taken = false, given = false;
    };
    static int declIndex(std::string_view pass);
    void take(int through);
    void give(int through);

    const CompiledGraph& graph_;
    Frame& frame_;
    std::vector<Held> held_;
    int done_ = -1;  // the last step's last declaration index
};

}  // namespace ssrt
