#include "denoise/denoise.h"

#include <algorithm>
#include <chrono>
#include <span>
#include <stdexcept>
#include <type_traits>

#include "core/plane_view.h"
#include "core/tiles.h"
#include "denoise/denoise_fields.h"
#include "denoise/reblur_kernel.h"

namespace ssrt {

void DenoiseSettings::validate() const { checkFields(kDenoiseFields, *this, "DenoiseSettings"); }

DenoiseSettings halfResolutionDiffuse(const DenoiseSettings& full) {
    DenoiseSettings s = full;
    s.diffusePrepassRadius =
        full.diffusePrepassRadius > 0.0f ? 0.5f * full.diffusePrepassRadius : 1.5f;
    s.minBlurRadius = 0.5f * full.minBlurRadius;
    s.maxBlurRadius = 0.25f * full.maxBlurRadius;
    s.historyFixStride = std::max(1, full.historyFixStride / 2);
    return s;
}

namespace {

// The rotation draws' sample counters: far above any ray generator's (samples < 64), so the
// kernels' rotations are not correlated with the rays' directions.
constexpr uint32_t kRotationStream = 0x10000;

// Times each pass (over both signals) for --stats.
class PassTimes {
public:
    explicit PassTimes(std::vector<DenoisePassTime>* out) : out_(out) {}
    template <class Fn>
    void run(const char* name, Fn&& fn) {
        const auto t0 = std::chrono::steady_clock::now();
        fn();
        if (!out_) return;
        const std::chrono::duration<double, std::milli> ms = std::chrono::steady_clock::now() - t0;
        // One entry per pass, summed over the two signals.
        const std::string key = std::string("denoise ") + name;
        for (DenoisePassTime& t : *out_)
            if (t.name == key) return void(t.ms += ms.count());
        out_->push_back({key, ms.count()});
    }

private:
    std::vector<DenoisePassTime>* out_;
};

struct Context {
    const DenoiseSettings& s;
    const DenoiseCall& in;
    DenoiseScratch& sc;
    const DenoiseHistory* previous;  // last frame's, of this size; null: none to read
    DenoiseHistory* next;            // null: no history to write (may be `previous`)
    // Which signals `previous` holds, decided before `next` (the same history, maybe) is
    // sized for this frame's signals.
    bool previousHas[2];
    Isa isa;
    int threads;
    TileGrid grid;
    ReblurFrame frame;
};

// The frame every pass reads: guides, cameras, the front end's classification and the tuning.
ReblurFrame makeFrame(const DenoiseCall& in, const DenoiseSettings& s, DenoiseScratch& sc,
                      const DenoiseHistory* previous, const TileGrid& grid) {
    const TraceCamera& cam = in.camera;
    ReblurFrame v;
    static_cast<GBufferView&>(v) = in.g;
    v.tilesX = grid.tilesX;
    v.tanHalfX = cam.tanHalfX;
    v.tanHalfY = cam.tanHalfY;
    std::copy_n(cam.viewToWorld, 9, v.viewToWorld);
    // NRD's GetFrustumSize: the frustum's short side at depth 1.
    v.frustum = 2.0f * (grid.width < grid.height ? cam.tanHalfX : cam.tanHalfY);
    v.frameIndex = in.frameIndex;
    v.signalZ[0] = sc.signalZ[0].row(0);
    v.signalZ[1] = sc.signalZ[1].row(0);
    v.tiles = sc.tiles.data();
    const float diagonal = cam.sceneDiagonal > 0.0f ? cam.sceneDiagonal : 1.0f;
    v.hitScale = {s.hitDistanceA * diagonal, s.hitDistanceB, s.hitDistanceC, s.hitDistanceD};
    if (previous && s.maxAccumulatedFrames > 0) {
        const DenoiseHistory& h = *previous;
        GBufferPlanesF::forEach(
            h.guide,
            [&](GBufferPlane which, const PlaneF& p) {
                GBufferView::at(v.prev, which) = p.empty() ? nullptr : p.row(0);
            },
            DenoiseHistory::kGuidePlanes);
        std::copy_n(h.camera.viewToWorld, 9, v.prevViewToWorld);
        v.prevTanHalfX = h.camera.tanHalfX;
        v.prevTanHalfY = h.camera.tanHalfY;
        // Both cameras' positions are measured from the same scene origin.
        for (int i = 0; i < 3; ++i) v.cameraDelta[i] = cam.position[i] - h.camera.position[i];
    }
    v.specularMaxRoughness = in.specularMaxRoughness;
    v.minBlurRadius = s.minBlurRadius;
    v.lobeFraction2 = s.lobeAngleFraction * s.lobeAngleFraction;
    v.roughnessFraction = s.roughnessFraction;
    v.planeDistance = s.planeDistanceSensitivity;
    v.minHitWeight = s.minHitDistanceWeight;
    v.maxAccumulatedFrames = float(s.maxAccumulatedFrames);
    v.maxFastAccumulatedFrames = float(s.maxFastAccumulatedFrames);
    v.disocclusion = s.disocclusionThreshold;
    v.fireflyScale = s.fireflyMinRelativeScale;
    v.virtualMotion = s.virtualMotion;
    v.historyFixFrames = float(s.historyFixFrames);
    v.historyFixStride = float(s.historyFixStride);
    return v;
}

// A signal's view as requireViews sees it, by its field's name where the caller left it
// unnamed (a view never set).
ViewShape named(ViewShape v, std::string_view field) {
    if (v.name.empty()) v.name = field;
    return v;
}

// The guides each signal needs, and its views: what it reads, and where it writes.
void checkViews(const DenoiseCall& in, int w, int h) {
    const bool diffuse = in.hasDiffuse(), specular = in.hasSpecular();
    requireGBuffer("denoise", in.g,
                   kGViewZ | kGNormal | kGMotion | (diffuse ? kGAlbedo | kGMetallic : 0u) |
                       (specular ? GBufferPlanes(kGRoughness) : 0u),
                   w, h);
    if (diffuse)
        requireViews(
            "denoise", w, h,
            {named(in.diffuse[0], "diffuse"), named(in.diffuse[1], "diffuse"),
             named(in.diffuse[2], "diffuse"), named(in.diffuseHitDistance, "diffuseHitDistance"),
             named(in.denoisedDiffuse[0], "denoisedDiffuse"),
             named(in.denoisedDiffuse[1], "denoisedDiffuse"),
             named(in.denoisedDiffuse[2], "denoisedDiffuse")});
    if (specular)
        requireViews(
            "denoise", w, h,
            {named(in.ssr[0], "ssr"), named(in.ssr[1], "ssr"), named(in.ssr[2], "ssr"),
             named(in.ssrOpacity, "ssrOpacity"), named(in.envSpecular[0], "envSpecular"),
             named(in.envSpecular[1], "envSpecular"), named(in.envSpecular[2], "envSpecular"),
             named(in.specularHitDistance, "specularHitDistance"),
             named(in.denoisedSpecular[0], "denoisedSpecular"),
             named(in.denoisedSpecular[1], "denoisedSpecular"),
             named(in.denoisedSpecular[2], "denoisedSpecular")});
    // (The history lengths only where asked for.)
    if (diffuse && in.diffuseFrames) requireViews("denoise", w, h, {in.diffuseFrames});
    if (specular && in.specularFrames) requireViews("denoise", w, h, {in.specularFrames});
}

void frontEnd(Context& c) {
    const DenoiseCall& in = c.in;
    ReblurPassArgs a;
    a.frame = c.frame;
    a.signals = in;  // (the traced signals: DenoiseSignals)
    a.noisyDiffuse = c.sc.noisyDiffuse.row(0);
    a.noisySpecular = c.sc.noisySpecular.row(0);
    a.signalZ[0] = c.sc.signalZ[0].row(0);
    a.signalZ[1] = c.sc.signalZ[1].row(0);
    a.tiles = c.sc.tiles.data();
    const auto fn = SSRT_DISPATCH(c.isa, reblurFrontEndTile);
    parallelForTiles(c.grid.count(), c.threads, [&](int tile) { fn(a, tile); });
}

// What every pass after the front end starts from: the frame, the signal, its input and output.
ReblurPassArgs passArgs(const Context& c, bool specular, const PlaneU64* in,
                        const SignalOut4& out) {
    ReblurPassArgs a;
    a.frame = c.frame;
    a.specular = specular;
    a.in = in->row(0);
    a.out = out;
    return a;
}

// Each pass's arguments for one signal; runPass runs them.
ReblurPassArgs spatial(Context& c, bool specular, ReblurSpatial pass, const PlaneU64* in,
                       const SignalOut4& out, PlaneU64* copy, const PlaneF* frames) {
    const DenoiseSettings& s = c.s;
    ReblurPassArgs a = passArgs(c, specular, in, out);
    a.pass = pass;
    if (copy) a.copy = copy->row(0);
    a.frames = frames ? frames->row(0) : nullptr;
    if (pass != ReblurSpatial::PreBlur) a.noFrames = 0.0f;  // (no temporal pass: no history)
    a.stream = kRotationStream + uint32_t(pass) * 2u + (specular ? 1u : 0u);
    const float blur = pass == ReblurSpatial::PostBlur ? 2.0f * s.maxBlurRadius : s.maxBlurRadius;
    a.radius = pass == ReblurSpatial::PreBlur
                   ? (specular ? s.specularPrepassRadius : s.diffusePrepassRadius)
                   : blur;
    if (pass == ReblurSpatial::Blur) a.maxFrames = float(s.blurMaxFrames);
    a.fractionScale = pass == ReblurSpatial::PreBlur ? 2.0f
                      : pass == ReblurSpatial::Blur  ? 1.0f
                                                     : 0.5f;
    return a;
}

ReblurPassArgs temporal(Context& c, bool specular, const PlaneU64* in, PlaneU64* out) {
    const int k = specular ? 1 : 0;
    ReblurPassArgs a = passArgs(c, specular, in, out->row(0));
    a.outFrames = c.sc.frames[k].row(0);
    a.outFast = c.sc.fast[k].row(0);
    if (c.frame.prev.viewZ && c.previousHas[k]) {
        const DenoiseHistory& h = *c.previous;
        a.prevSignal = (specular ? h.specular : h.diffuse).row(0);
        a.prevFrames = (specular ? h.specularFrames : h.diffuseFrames).row(0);
        a.prevFast = (specular ? h.specularFast : h.diffuseFast).row(0);
    }
    return a;
}

ReblurPassArgs historyFix(Context& c, bool specular, const PlaneU64* in, PlaneU64* out) {
    const DenoiseSettings& s = c.s;
    const int k = specular ? 1 : 0;
    ReblurPassArgs a = passArgs(c, specular, in, out->row(0));
    // (Without the temporal pass no pixel has a history, and the fast history is the input's
    // luma, as that pass would have left them.)
    a.frames = c.in.temporal ? c.sc.frames[k].row(0) : nullptr;
    // The fast history clamps the slow one only where it is faster.
    const bool clamp = s.maxFastAccumulatedFrames < s.maxAccumulatedFrames;
    a.fast = clamp && c.in.temporal ? c.sc.fast[k].row(0) : nullptr;
    a.fastIsInputLuma = clamp && !c.in.temporal;
    return a;
}

using PassKernel = void (*)(const ReblurPassArgs&, int);

// One pass over the signals in `args` (null: that signal skips it) in one loop over the
// tiles: a tile goes through the diffuse's kernel, then the specular's, then `afterTile`
// (the post-blur's: the history's commit). Each kernel writes only its own signal's planes, so
// the bits are those of one signal's pass after the other's.
template <class AfterTile>
void runPass(Context& c, PassKernel fn, const ReblurPassArgs* const (&args)[2],
             const AfterTile& afterTile) {
    parallelForTiles(c.grid.count(), c.threads, [&](int tile) {
        for (const ReblurPassArgs* a : args)
            if (a) fn(*a, tile);
        afterTile(tile);
    });
}
void runPass(Context& c, PassKernel fn, const ReblurPassArgs* const (&args)[2]) {
    runPass(c, fn, args, [](int) {});
}

// The history's guides and accumulation speeds (+ 1: the next frame's count includes this
// one) of one tile, for the next frame: run on each tile right after its post-blur (the
// tile's guides and speeds still in cache), not in a loop of its own. It reads the G-buffer,
// the signals' masks and this frame's speeds, which no pass writes after the temporal one, and
// writes the history's guides and speeds, which only the temporal pass reads (the post-blur
// reads neither, and the history's signals it writes itself), so the bits are those of a
// commit after the post-blur.
void commitHistoryTile(const Context& c, int tile) {
    DenoiseHistory& h = *c.next;
    const DenoiseCall& in = c.in;
    PlaneF* const frames[2] = {&h.diffuseFrames, &h.specularFrames};
    const bool signals[2] = {in.hasDiffuse(), in.hasSpecular()};
    // The guides the history keeps (roughness only with the specular signal: ensureSizes).
    struct Guide {
        const float* from;
        PlaneF* to;
    };
    Guide guides[kGBufferPlaneCount];
    int n = 0;
    GBufferPlanesF::forEach(
        h.guide,
        [&](GBufferPlane which, PlaneF& p) {
            if (!p.empty()) guides[n++] = {GBufferView::at(in.g, which), &p};
        },
        DenoiseHistory::kGuidePlanes);
    const TileRect r = c.grid.rect(tile);
    for (int y = r.y0; y < r.y1; ++y) {
        const std::size_t o = std::size_t(y) * in.g.stride;
        for (const Guide& g : std::span(guides, std::size_t(n)))
            std::copy(g.from + o + r.x0, g.from + o + r.x1, g.to->row(y) + r.x0);
        for (int k = 0; k < 2; ++k) {
            if (!signals[k]) continue;
            const float* a = c.sc.frames[k].row(y);
            const float* m = c.sc.signalZ[k].row(y);  // 0: no pixel
            float* out = frames[k]->row(y);
            for (int x = r.x0; x < r.x1; ++x) out[x] = m[x] > 0.0f ? a[x] + 1.0f : 0.0f;
        }
    }
}

// The rest of the history's commit, once the post-blur has committed every tile's: the fast
// histories (this frame's planes, swapped in) and the camera.
void finishHistory(Context& c) {
    DenoiseHistory& h = *c.next;
    if (c.in.hasDiffuse()) std::swap(h.diffuseFast, c.sc.fast[0]);
    if (c.in.hasSpecular()) std::swap(h.specularFast, c.sc.fast[1]);
    h.camera = c.in.camera;
    h.valid = true;
}

// The signals through every pass after the front end, each pass once over both (runPass); the
// post-blur writes the outputs and the history (its signals, and tile by tile its guides and
// speeds: commitHistoryTile). A pass's result is a resource named for it (DenoiseScratch),
// taken from the pool as the pass starts; the pass's input goes back to the pool once it has
// run, where the next pass's result takes its memory.
void denoiseSignals(Context& c, PlanePool& pool, PassTimes& times) {
    DenoiseScratch& sc = c.sc;
    const DenoiseSettings& s = c.s;
    const int w = c.grid.width, h = c.grid.height;
    const bool on[2] = {c.in.hasDiffuse(), c.in.hasSpecular()};
    PlaneU64* current[2] = {&sc.noisyDiffuse, &sc.noisySpecular};
    // (null without the temporal pass: the blurs take 0 frames)
    const PlaneF* frames[2] = {c.in.temporal ? &sc.frames[0] : nullptr,
                               c.in.temporal ? &sc.frames[1] : nullptr};
    // A pass over the signals `runs` says, each into its plane of `results`.
    const auto step = [&](const char* name, PassKernel fn, PlaneU64(&results)[2],
                          const bool(&runs)[2], auto&& build) {
        ReblurPassArgs args[2];
        const ReblurPassArgs* run[2] = {};
        for (int k = 0; k < 2; ++k) {
            if (!on[k] || !runs[k]) continue;
            pool.take(results[k], w, h);
            args[k] = build(k == 1, current[k], &results[k]);
            run[k] = &args[k];
        }
        times.run(name, [&] { runPass(c, fn, run); });
        for (int k = 0; k < 2; ++k) {
            if (!run[k]) continue;
            pool.give(*current[k]);
            current[k] = &results[k];
        }
    };
    const bool preBlur[2] = {s.diffusePrepassRadius > 0.0f, s.specularPrepassRadius > 0.0f};
    const bool all[2] = {true, true};
    if (preBlur[0] || preBlur[1])
        step("pre-blur", SSRT_DISPATCH(c.isa, reblurSpatialTile), sc.preBlurred, preBlur,
             [&](bool specular, const PlaneU64* in, PlaneU64* out) {
                 return spatial(c, specular, ReblurSpatial::PreBlur, in, out->row(0), nullptr,
                                nullptr);
             });
    if (c.in.temporal)
        step("temporal", SSRT_DISPATCH(c.isa, reblurTemporalTile), sc.temporal, all,
             [&](bool specular, const PlaneU64* in, PlaneU64* out) {
                 return temporal(c, specular, in, out);
             });
    step("history fix", SSRT_DISPATCH(c.isa, reblurHistoryFixTile), sc.fixed, all,
         [&](bool specular, const PlaneU64* in, PlaneU64* out) {
             return historyFix(c, specular, in, out);
         });
    step("blur", SSRT_DISPATCH(c.isa, reblurSpatialTile), sc.blurred, all,
         [&](bool specular, const PlaneU64* in, PlaneU64* out) {
             return spatial(c, specular, ReblurSpatial::Blur, in, out->row(0), nullptr,
                            frames[specular ? 1 : 0]);
         });
    // The post-blur's result, RGB to the output and all four channels to the history. (The
    // output has no hit distance: the post-blur writes that channel to the history only.)
    ReblurPassArgs args[2];
    const ReblurPassArgs* run[2] = {};
    for (int k = 0; k < 2; ++k) {
        if (!on[k]) continue;
        const bool specular = k == 1;
        PlaneU64* history = nullptr;
        if (c.next) history = specular ? &c.next->specular : &c.next->diffuse;
        SignalOut4 out;
        const OutF* const outputs = specular ? c.in.denoisedSpecular : c.in.denoisedDiffuse;
        for (int ch = 0; ch < 3; ++ch) out[ch] = outputs[ch].data;
        args[k] =
            spatial(c, specular, ReblurSpatial::PostBlur, current[k], out, history, frames[k]);
        run[k] = &args[k];
    }
    // The history length the EXR shows: frames behind each pixel (copied tile by tile after
    // the tile's post-blur, which reads the speeds and not the outputs' copy of them).
    const OutF framesOut[2] = {c.in.diffuseFrames, c.in.specularFrames};
    bool lengths[2] = {};
    for (int k = 0; k < 2; ++k) {
        if (!on[k] || !framesOut[k]) continue;
        if (frames[k]) lengths[k] = true;
        else
            for (int y = 0; y < framesOut[k].height; ++y)
                std::fill_n(framesOut[k].row(y), framesOut[k].width, 0.0f);
    }
    // (Its time includes, per tile, the history lengths' copy and the history's commit,
    // commitHistoryTile; the "history" line is what is left of the commit, finishHistory.)
    times.run("post-blur", [&] {
        runPass(c, SSRT_DISPATCH(c.isa, reblurSpatialTile), run, [&](int tile) {
            const TileRect r = c.grid.rect(tile);
            for (int k = 0; k < 2; ++k)
                if (lengths[k])
                    for (int y = r.y0; y < r.y1; ++y)
                        std::copy(frames[k]->row(y) + r.x0, frames[k]->row(y) + r.x1,
                                  framesOut[k].row(y) + r.x0);
            if (c.next) commitHistoryTile(c, tile);
        });
    });
    for (int k = 0; k < 2; ++k)
        if (on[k]) pool.give(*current[k]);
}

// A scratch plane sized for the signals present (`on`), from the pool where there is one.
template <class T>
void keepScratch(bool on, Plane<T>& p, int w, int h, PlanePool* pool) {
    if (!pool) {
        if (on) p.ensureSize(w, h);
        else p = Plane<T>();
    } else if (on) {
        pool->take(p, w, h);
    } else {
        pool->give(p);
    }
}

// The scratch the temporal pass writes: the accumulation speeds and the fast histories (taken
// once the front end has read the signals; each pass's result is taken as it starts).
void ensurePassScratch(int w, int h, DenoiseScratch& sc, bool diffuse, bool specular, bool temporal,
                       PlanePool* pool) {
    for (int i = 0; i < 2; ++i) {
        const bool on = (i == 0 ? diffuse : specular) && temporal;
        keepScratch(on, sc.frames[i], w, h, pool);
        keepScratch(on, sc.fast[i], w, h, pool);
    }
}

// The front end's scratch (the noisy signals and where they exist) and the history.
void ensureSizes(int w, int h, DenoiseScratch& sc, DenoiseHistory* history, bool diffuse,
                 bool specular, const TileGrid& grid, PlanePool* pool) {
    const auto keepIf = [&](bool on, auto& p) {
        if (on) p.ensureSize(w, h);
        else p = std::decay_t<decltype(p)>();
    };
    // Only the signals present.
    keepScratch(diffuse, sc.noisyDiffuse, w, h, pool);
    keepScratch(specular, sc.noisySpecular, w, h, pool);
    for (int i = 0; i < 2; ++i) keepScratch(i == 0 ? diffuse : specular, sc.signalZ[i], w, h, pool);
    sc.tiles.assign(std::size_t(grid.count()), 0);
    if (!history) return;
    // The guides, and each signal's own planes only where the signal is (roughness guides the
    // specular alone).
    GBufferPlanesF::forEach(
        history->guide,
        [&](GBufferPlane which, PlaneF& p) { keepIf(which != kGRoughness || specular, p); },
        DenoiseHistory::kGuidePlanes);
    keepIf(diffuse, history->diffuse);
    keepIf(specular, history->specular);
    keepIf(diffuse, history->diffuseFrames), keepIf(diffuse, history->diffuseFast);
    keepIf(specular, history->specularFrames), keepIf(specular, history->specularFast);
}

}  // namespace

void denoise(Isa isa, const DenoiseSettings& settings, const DenoiseCall& in,
             DenoiseHistory* history, bool reset, DenoiseScratch& scratch, int threads,
             std::vector<DenoisePassTime>* times) {
    settings.validate();
    const int w = in.camera.width, h = in.camera.height;
    if (w <= 0 || h <= 0) throw std::invalid_argument("denoise: empty camera");
    checkViews(in, w, h);
    const bool diffuse = in.hasDiffuse(), specular = in.hasSpecular();
    const TileGrid grid(w, h);
    const bool readHistory = history && !reset && history->usableAt(w, h);
    const DenoiseHistory* previous = readHistory ? history : nullptr;
    DenoiseHistory* next = in.replaceHistory ? history : nullptr;
    if (next && !readHistory) next->valid = false;
    if (!in.temporal && (previous || next))
        throw std::logic_error("denoise: a history is read or kept without the temporal pass");
    const bool previousHas[2] = {previous && previous->hasSignal(false),
                                 previous && previous->hasSignal(true)};
    ensureSizes(w, h, scratch, next, diffuse, specular, grid, in.pool);
    Context c{settings, in,
              scratch,  previous,
              next,     {previousHas[0], previousHas[1]},
              isa,      threads,
              grid,     makeFrame(in, settings, scratch, previous, grid)};
    PassTimes pt(times);
    pt.run("front end", [&] { frontEnd(c); });
    if (in.signalsRead) in.signalsRead();
    ensurePassScratch(w, h, scratch, diffuse, specular, in.temporal, in.pool);
    PlanePool local;  // (without the caller's: each pass's result freed once read)
    denoiseSignals(c, in.pool ? *in.pool : local, pt);
    if (next) pt.run("history", [&] { finishHistory(c); });
    if (in.pool) in.pool->give(scratch);
}

}  // namespace ssrt
