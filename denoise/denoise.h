// The denoiser: REBLUR (NVIDIA NRD, "ReBLUR: A Hierarchical Recurrent Denoiser", Ray Tracing
// Gems II ch. 49; walked through pass by pass in shared/seeds/003) on the CPU, deterministic
// to the bit. It reads only planes: the G-buffer's guides, the traced signals (SSR's and
// SSGI's radiance with their hit distances) and a caller-owned history; it writes the
// denoised diffuse and specular radiance and each pixel's history length.
//
// Passes, in order (NRD's names), each a per-tile kernel over lanes across x that writes only
// its own tile of its own output planes (never the plane it reads):
//   front end     sanitises the signals (NaN, infinity -> 0), builds the specular radiance
//                 SSR over the environment, normalises hit distances; classifies tiles (a
//                 tile without a surface pixel, or without a signal, skips the passes below)
//   pre-blur      8 taps rotated per frame, radius from the hit distance
//   temporal      surface-motion reprojection with disocclusion by depth, Catmull-Rom history
//                 with a bilinear fallback where a tap is occluded, the accumulation speed
//                 (frames, capped), the fast history, the firefly suppressor; for specular
//                 also the virtual motion of the reflection, blended by confidence (only
//                 with a history to read or keep: DenoiseCall::temporal)
//   history fix   a wider reconstruction for pixels younger than historyFixFrames, and the
//                 fast history's clamp of the slow one (anti-lag)
//   blur          8 taps, radius shrinking as the history grows
//   post-blur     twice the radius, stricter weights; writes the outputs and the history's
//                 signals the next frame reads
//   history       the history's commit: its guides and speeds, tile by tile (a scheduler may
//                 run it in the post-blur's loop: DenoiseStep), then the fast histories swapped
//                 in and the camera
// (REBLUR's temporal stabilisation is not built: the accumulation's own window already keeps
// a still camera's flicker far under the bar; see the closing note of issue 17.)
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/camera.h"
#include "core/float_planes.h"
#include "core/gbuffer_view.h"
#include "core/image.h"
#include "core/isa.h"
#include "core/plane_pool.h"
#include "core/plane_table.h"
#include "core/tiles.h"
#include "denoise/denoise_settings.h"
#include "denoise/reblur_kernel.h"

namespace ssrt {

// One frame's call: the traced signals (DenoiseSignals, views of the frame's size), the guides,
// where it writes, and the rest. (NRD's dispatch: its common settings and the pool of the
// caller's resources, inputs and outputs, in one.)
struct DenoiseCall : DenoiseSignals {
    TraceCamera camera;
    uint32_t frameIndex = 0;  // rotates the spatial kernels (counter RNG, core/rng.h)
    // The guides: viewZ (0: background), normal and motion; roughness for the specular signal
    // alone; albedo with metallic (where the diffuse signal exists) for the diffuse alone.
    GBufferView g;
    // Where it writes, the caller's planes, sized by the caller to the frame: each signal's
    // denoised incoming radiance (diffuse: what the composite multiplies by albedo; specular:
    // by specWeight), required where the signal is given; the frames of history behind each
    // pixel (0: none), planes only to be looked at: absent, not made.
    OutF denoisedDiffuse[3], denoisedSpecular[3];
    OutF diffuseFrames, specularFrames;
    // Pixels this rough or rougher have no specular signal (SSR's roughness fade end).
    float specularMaxRoughness = 1.0f;
    // false: the history is read but left as it was (no later frame reads this one's): the
    // same output, without writing the next history.
    bool replaceHistory = true;
    // false: the temporal pass does not run (the frame graph culls it where no history is read
    // or kept: it would copy its input, with no speed and its own luma as the fast history);
    // the history fix reads its input instead, and the same output follows, bit for bit.
    // Throws std::logic_error if a history is read or replaced.
    bool temporal = true;
    // Where the scratch's planes come from, and go back to after the call (null: the scratch
    // keeps its state planes between calls; the signals and each pass's result are freed once
    // read either way, their memory kept resident by the planes' range, core/plane_memory.h).
    PlanePool* pool = nullptr;
    // Called once the front end has read the signals above, before the scratch planes the
    // later passes write are taken from the pool: a caller whose signal planes are pooled
    // gives them back here, and the passes reuse their memory (optional).
    std::function<void()> signalsRead;
};

// What one frame leaves the next: the post-blur's result (REBLUR is recurrent), the
// accumulation speeds, the fast histories, and the guides and camera it was made with. A
// signal's planes are kept only when that frame had the signal (hasSignal); a signal without
// them starts afresh.
struct DenoiseHistory : PlaneTable<DenoiseHistory> {
    // The guides of the edge stops (f32): viewZ, normal, and roughness with the specular.
    static constexpr GBufferPlanes kGuidePlanes = kGViewZ | kGNormal | kGRoughness;
    GBufferPlanesF guide;
    PlaneU64 diffuse, specular;  // RGB and normalised hit distance, f16x4
    PlaneF diffuseFrames, specularFrames;
    PlaneU16 diffuseFast, specularFast;  // luma, f16
    TraceCamera camera;
    bool valid = false;

    // (Named as the renderer's resource table names their channels at full resolution,
    // renderer/resources.cpp: tests/renderer/denoise_formats_test.cpp holds each plane's element
    // size to the format declared there.)
    template <class G, class Fn>
    static void table(G& g, Fn& fn) {
        forEachGBufferChannel("history.denoise.guide.", g.guide, kGuidePlanes, fn);
        fn("history.denoise.diffuse", g.diffuse);
        fn("history.denoise.specular", g.specular);
        fn("history.denoise.diffuseFrames", g.diffuseFrames);
        fn("history.denoise.specularFrames", g.specularFrames);
        fn("history.denoise.diffuseFast", g.diffuseFast);
        fn("history.denoise.specularFast", g.specularFast);
    }

    bool usableAt(int width, int height) const {
        return valid && guide.viewZ.width() == width && guide.viewZ.height() == height;
    }
    // It holds that signal's planes (only the signals of the frame that made it are kept).
    bool hasSignal(bool specular) const {
        return !(specular ? specularFrames : diffuseFrames).empty();
    }
};

// Transient planes. The signals (radiance, hit distance, fast luma) are f16
// (core/pixel_formats.h), decoded on load and encoded on store by the passes, which compute in
// f32: radiance and hit distance as f16x4, a pixel's four in one 64-bit element (a tap one
// gather, not four). Where the signal exists, its depth and the accumulation speeds are f32.
// Each pass's result is a plane named for the pass (NRD names its resources so), per signal;
// a pass reads only the one before it, so a result is taken from the pool as its pass starts
// and its input goes back as it ends: a signal holds two of them at a time.
struct DenoiseScratch : PlaneTable<DenoiseScratch> {
    // The front end's, per signal: RGB and the normalised hit distance.
    PlaneU64 noisyDiffuse, noisySpecular;
    // Per signal (diffuse, specular), sized only for the signals given:
    PlaneU64 preBlurred[2], temporal[2], fixed[2], blurred[2];  // each pass's result
    PlaneF signalZ[2];           // viewZ where the signal exists, else 0
    PlaneF frames[2];            // this frame's accumulation speeds
    PlaneU16 fast[2];            // this frame's fast luma
    std::vector<uint8_t> tiles;  // per tile: bit 0 diffuse, bit 1 specular

    // (Named as the renderer's resource table names their channels at full resolution,
    // renderer/resources.cpp; the half frame's add "half.".)
    template <class G, class Fn>
    static void table(G& g, Fn& fn) {
        fn("noisy.diffuse", g.noisyDiffuse), fn("noisy.specular", g.noisySpecular);
        fn("preBlurred.diffuse", g.preBlurred[0]), fn("preBlurred.specular", g.preBlurred[1]);
        fn("temporal.diffuse", g.temporal[0]), fn("temporal.specular", g.temporal[1]);
        fn("fixed.diffuse", g.fixed[0]), fn("fixed.specular", g.fixed[1]);
        fn("blurred.diffuse", g.blurred[0]), fn("blurred.specular", g.blurred[1]);
        fn("state.diffuse.signalZ", g.signalZ[0]), fn("state.specular.signalZ", g.signalZ[1]);
        fn("state.diffuse.frames", g.frames[0]), fn("state.specular.frames", g.frames[1]);
        fn("fast.diffuse", g.fast[0]), fn("fast.specular", g.fast[1]);
    }
};

struct DenoisePassTime {
    std::string name;
    double ms = 0.0;
};

// One pass of a frame's denoising, as a scheduler runs it: its set-up (the planes it writes
// taken from the pool, its arguments made), its kernel on one tile (which writes only that
// tile of the pass's own results) and its finish (the planes it read last given back). A
// pass's set-up runs after the set-ups of the passes before it and before its first tile; its
// finish after its last tile. Passes that read what the pass before wrote only at their own
// pixel may share that pass's loop over the tiles, set-ups first, finishes last (the frame
// graph's chains, renderer/frame_graph.h): each tile through one pass, then the next.
struct DenoiseStep {
    std::string_view name;  // "front end", "pre-blur", "temporal", "history fix", "blur",
                            // "post-blur", "history" (the history's commit)
    std::function<void()> setUp;
    std::function<void(int tile)> tile;
    std::function<void()> finish;
};

// One frame's denoising as its passes (the ones this call runs, in order); denoise() below runs
// them one loop each. The call, settings, history and scratch are read through references and
// must outlive it. The constructor checks the call as denoise() does (and throws as it does);
// nothing is taken from the pool before the first set-up.
class DenoiseRun {
public:
    DenoiseRun(Isa isa, const DenoiseSettings& settings, const DenoiseCall& call,
               DenoiseHistory* history, bool reset, DenoiseScratch& scratch, int threads);
    ~DenoiseRun();
    DenoiseRun(const DenoiseRun&) = delete;
    DenoiseRun& operator=(const DenoiseRun&) = delete;

    const TileGrid& grid() const;
    const std::vector<DenoiseStep>& steps() const;
    // The step called `name`; null if this call does not run it.
    const DenoiseStep* step(std::string_view name) const;

    struct State;

private:
    std::unique_ptr<State> state_;
    std::vector<DenoiseStep> steps_;
};

// Denoises one frame into the call's outputs. `history` (null: none, every pixel starts afresh)
// is read when usable at this size and `reset` is false, then replaced with this frame's
// (unless call.replaceHistory is false). Throws std::invalid_argument on a missing or
// mis-sized plane. Appends each pass's time to `times` (optional).
void denoise(Isa isa, const DenoiseSettings& settings, const DenoiseCall& call,
             DenoiseHistory* history, bool reset, DenoiseScratch& scratch, int threads,
             std::vector<DenoisePassTime>* times = nullptr);

}  // namespace ssrt
