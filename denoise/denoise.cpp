#include "denoise/denoise.h"

#include <algorithm>
#include <array>
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

// One frame's run: what its passes share.
struct DenoiseRun::State {
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
    bool on[2];           // the signals given: diffuse, specular
    ReblurFrame frame{};  // made by the front end's set-up
    PlanePool local;      // (without the caller's pool: each pass's result freed once read)
    // Each signal's latest result: the plane the next pass reads.
    PlaneU64* current[2] = {};
    // Each signal's accumulation speeds (null without the temporal pass: the blurs take 0).
    const PlaneF* frames[2] = {};
    // A pass's arguments per signal (null: the signal skips it), its kernel, and the planes
    // it gives back once run.
    struct Pass {
        ReblurPassArgs args[2];
        const ReblurPassArgs* run[2] = {};
        void (*kernel)(const ReblurPassArgs&, int) = nullptr;
        PlaneU64* read[2] = {};
    };
    std::vector<Pass> passes;  // one per step, in order
    OutF lengths[2];           // the history lengths the post-blur copies the speeds to

    PlanePool& pool() { return in.pool ? *in.pool : local; }
};

namespace {

using State = DenoiseRun::State;

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

// The front end's arguments: the traced signals in, the noisy signals and the tile classes out.
ReblurPassArgs frontEndArgs(const State& c) {
    ReblurPassArgs a;
    a.frame = c.frame;
    a.signals = c.in;  // (the traced signals: DenoiseSignals)
    a.noisyDiffuse = c.sc.noisyDiffuse.row(0);
    a.noisySpecular = c.sc.noisySpecular.row(0);
    a.signalZ[0] = c.sc.signalZ[0].row(0);
    a.signalZ[1] = c.sc.signalZ[1].row(0);
    a.tiles = c.sc.tiles.data();
    return a;
}

// What every pass after the front end starts from: the frame, the signal, its input and output.
ReblurPassArgs passArgs(const State& c, bool specular, const PlaneU64* in, const SignalOut4& out) {
    ReblurPassArgs a;
    a.frame = c.frame;
    a.specular = specular;
    a.in = in->row(0);
    a.out = out;
    return a;
}

// Each pass's arguments for one signal (signalStep makes its step of them).
ReblurPassArgs spatial(const State& c, bool specular, ReblurSpatial pass, const PlaneU64* in,
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
    if (pass == ReblurSpatial::PostBlur && frames && s.postBlurMaxFrames <= kMaxDenoiseFrames) {
        a.maxFrames = float(s.postBlurMaxFrames);
        a.steadyFast = c.sc.fast[specular ? 1 : 0].row(0);
    }
    a.fractionScale = pass == ReblurSpatial::PreBlur ? 2.0f
                      : pass == ReblurSpatial::Blur  ? 1.0f
                                                     : 0.5f;
    return a;
}

ReblurPassArgs temporal(const State& c, bool specular, const PlaneU64* in, PlaneU64* out) {
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

ReblurPassArgs historyFix(const State& c, bool specular, const PlaneU64* in, PlaneU64* out) {
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

// The history's guides and accumulation speeds (+ 1: the next frame's count includes this
// one) of one tile, for the next frame (the "history" step, which may share the post-blur's
// loop: the tile's guides and speeds still in cache). It reads the G-buffer,
// the signals' masks and this frame's speeds, which no pass writes after the temporal one, and
// writes the history's guides and speeds, which only the temporal pass reads (the post-blur
// reads neither, and the history's signals it writes itself), so the bits are those of a
// commit after the post-blur.
void commitHistoryTile(const State& c, int tile) {
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
void finishHistory(State& c) {
    DenoiseHistory& h = *c.next;
    if (c.in.hasDiffuse()) std::swap(h.diffuseFast, c.sc.fast[0]);
    if (c.in.hasSpecular()) std::swap(h.specularFast, c.sc.fast[1]);
    h.camera = c.in.camera;
    h.valid = true;
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

// The step a pass makes: its set-up takes each running signal's result from the pool (as its
// pass starts, so it reuses the memory of what earlier passes gave back) and builds its
// arguments with `build(specular, in, out)`; its tile runs the kernel on each signal, the
// diffuse's then the specular's (each writes only its own signal's planes, so the bits are
// those of one signal's pass after the other's); its finish gives the pass's inputs back.
template <class Build>
DenoiseStep signalStep(State& st, std::string_view name, void (*kernel)(const ReblurPassArgs&, int),
                       PlaneU64 (*results)[2], const bool (&runs)[2], Build build,
                       std::function<void()> before = {}) {
    const std::size_t i = st.passes.size();
    st.passes.emplace_back();
    st.passes[i].kernel = kernel;
    State* s = &st;
    return {name,
            [s, i, results, run = std::array<bool, 2>{runs[0], runs[1]}, build, before] {
                if (before) before();
                State::Pass& p = s->passes[i];
                for (int k = 0; k < 2; ++k) {
                    if (!s->on[k] || !run[std::size_t(k)]) continue;
                    PlaneU64* out = results ? &(*results)[k] : nullptr;
                    if (out) s->pool().take(*out, s->grid.width, s->grid.height);
                    p.args[k] = build(k == 1, s->current[k], out);
                    p.run[k] = &p.args[k];
                    p.read[k] = s->current[k];
                    if (out) s->current[k] = out;
                }
            },
            [s, i](int tile) {
                const State::Pass& p = s->passes[i];
                for (const ReblurPassArgs* a : p.run)
                    if (a) p.kernel(*a, tile);
            },
            [s, i] {
                for (PlaneU64* r : s->passes[i].read)
                    if (r) s->pool().give(*r);
            }};
}

// The steps of one frame, in order: the front end, then each pass after it over the signals
// (the post-blur writes the outputs and the history's signals), then the history's commit.
std::vector<DenoiseStep> makeSteps(State& st) {
    const DenoiseSettings& s = st.s;
    const DenoiseCall& in = st.in;
    DenoiseScratch& sc = st.sc;
    State* c = &st;
    std::vector<DenoiseStep> steps;
    // Front end: the scratch sized (no pool plane is taken before it), the frame made.
    st.passes.emplace_back();
    steps.push_back({"front end",
                     [c] {
                         State& t = *c;
                         ensureSizes(t.grid.width, t.grid.height, t.sc, t.next, t.on[0], t.on[1],
                                     t.grid, t.in.pool);
                         t.frame = makeFrame(t.in, t.s, t.sc, t.previous, t.grid);
                         t.current[0] = &t.sc.noisyDiffuse;
                         t.current[1] = &t.sc.noisySpecular;
                         for (int k = 0; k < 2; ++k)
                             t.frames[k] = t.in.temporal ? &t.sc.frames[k] : nullptr;
                         State::Pass& p = t.passes[0];
                         p.kernel = SSRT_DISPATCH(t.isa, reblurFrontEndTile);
                         p.args[0] = frontEndArgs(t);
                         p.run[0] = &p.args[0];
                     },
                     [c](int tile) { c->passes[0].kernel(c->passes[0].args[0], tile); },
                     [c] {
                         if (c->in.signalsRead) c->in.signalsRead();
                     }});
    // The scratch the temporal pass writes (the speeds and fast histories), taken with the
    // first pass after the front end.
    const auto passScratch = [c] {
        State& t = *c;
        ensurePassScratch(t.grid.width, t.grid.height, t.sc, t.on[0], t.on[1], t.in.temporal,
                          t.in.pool);
    };
    bool scratchTaken = false;
    const auto firstAfterFrontEnd = [&]() -> std::function<void()> {
        if (scratchTaken) return {};
        scratchTaken = true;
        return passScratch;
    };
    const bool preBlur[2] = {s.diffusePrepassRadius > 0.0f, s.specularPrepassRadius > 0.0f};
    const bool all[2] = {true, true};
    if ((st.on[0] && preBlur[0]) || (st.on[1] && preBlur[1]))
        steps.push_back(signalStep(
            st, "pre-blur", SSRT_DISPATCH(st.isa, reblurSpatialTile), &sc.preBlurred, preBlur,
            [c](bool specular, const PlaneU64* from, PlaneU64* to) {
                return spatial(*c, specular, ReblurSpatial::PreBlur, from, to->row(0), nullptr,
                               nullptr);
            },
            firstAfterFrontEnd()));
    if (in.temporal)
        steps.push_back(signalStep(
            st, "temporal", SSRT_DISPATCH(st.isa, reblurTemporalTile), &sc.temporal, all,
            [c](bool specular, const PlaneU64* from, PlaneU64* to) {
                return temporal(*c, specular, from, to);
            },
            firstAfterFrontEnd()));
    steps.push_back(signalStep(
        st, "history fix", SSRT_DISPATCH(st.isa, reblurHistoryFixTile), &sc.fixed, all,
        [c](bool specular, const PlaneU64* from, PlaneU64* to) {
            return historyFix(*c, specular, from, to);
        },
        firstAfterFrontEnd()));
    steps.push_back(signalStep(st, "blur", SSRT_DISPATCH(st.isa, reblurSpatialTile), &sc.blurred,
                               all, [c](bool specular, const PlaneU64* from, PlaneU64* to) {
                                   return spatial(*c, specular, ReblurSpatial::Blur, from,
                                                  to->row(0), nullptr, c->frames[specular ? 1 : 0]);
                               }));
    // The post-blur's result, RGB to the output and all four channels to the history. (The
    // output has no hit distance: the post-blur writes that channel to the history only.)
    DenoiseStep post = signalStep(
        st, "post-blur", SSRT_DISPATCH(st.isa, reblurSpatialTile), nullptr, all,
        [c](bool specular, const PlaneU64* from, PlaneU64*) {
            PlaneU64* history = nullptr;
            if (c->next) history = specular ? &c->next->specular : &c->next->diffuse;
            SignalOut4 out;
            const OutF* const outputs = specular ? c->in.denoisedSpecular : c->in.denoisedDiffuse;
            for (int ch = 0; ch < 3; ++ch) out[ch] = outputs[ch].data;
            return spatial(*c, specular, ReblurSpatial::PostBlur, from, out, history,
                           c->frames[specular ? 1 : 0]);
        });
    // The history lengths the EXR shows: the frames behind each pixel, copied tile by tile after
    // the tile's post-blur (which reads the speeds, not their copy); all 0 without the temporal
    // pass.
    post.setUp = [c, setUp = std::move(post.setUp)] {
        setUp();
        const OutF lengths[2] = {c->in.diffuseFrames, c->in.specularFrames};
        for (int k = 0; k < 2; ++k) {
            c->lengths[k] = {};
            if (!c->on[k] || !lengths[k]) continue;
            if (c->frames[k]) c->lengths[k] = lengths[k];
            else
                for (int y = 0; y < lengths[k].height; ++y)
                    std::fill_n(lengths[k].row(y), lengths[k].width, 0.0f);
        }
    };
    post.tile = [c, tile = std::move(post.tile)](int t) {
        tile(t);
        const TileRect r = c->grid.rect(t);
        for (int k = 0; k < 2; ++k)
            if (c->lengths[k])
                for (int y = r.y0; y < r.y1; ++y)
                    std::copy(c->frames[k]->row(y) + r.x0, c->frames[k]->row(y) + r.x1,
                              c->lengths[k].row(y) + r.x0);
    };
    steps.push_back(std::move(post));
    if (st.next)
        steps.push_back({"history",
                         {},
                         [c](int tile) { commitHistoryTile(*c, tile); },
                         [c] { finishHistory(*c); }});
    // Once the last step has run, the scratch goes back to the caller's pool.
    steps.back().finish = [c, finish = std::move(steps.back().finish)] {
        if (finish) finish();
        if (c->in.pool) c->in.pool->give(c->sc);
    };
    return steps;
}

}  // namespace

DenoiseRun::DenoiseRun(Isa isa, const DenoiseSettings& settings, const DenoiseCall& in,
                       DenoiseHistory* history, bool reset, DenoiseScratch& scratch, int threads) {
    settings.validate();
    const int w = in.camera.width, h = in.camera.height;
    if (w <= 0 || h <= 0) throw std::invalid_argument("denoise: empty camera");
    checkViews(in, w, h);
    const bool readHistory = history && !reset && history->usableAt(w, h);
    const DenoiseHistory* previous = readHistory ? history : nullptr;
    DenoiseHistory* next = in.replaceHistory ? history : nullptr;
    if (!in.temporal && (previous || next))
        throw std::logic_error("denoise: a history is read or kept without the temporal pass");
    if (next && !readHistory) next->valid = false;
    state_.reset(
        new State{settings,
                  in,
                  scratch,
                  previous,
                  next,
                  {previous && previous->hasSignal(false), previous && previous->hasSignal(true)},
                  isa,
                  threads,
                  TileGrid(w, h),
                  {in.hasDiffuse(), in.hasSpecular()}});
    steps_ = makeSteps(*state_);
}

DenoiseRun::~DenoiseRun() = default;

const TileGrid& DenoiseRun::grid() const { return state_->grid; }

const std::vector<DenoiseStep>& DenoiseRun::steps() const { return steps_; }

const DenoiseStep* DenoiseRun::step(std::string_view name) const {
    for (const DenoiseStep& s : steps_)
        if (s.name == name) return &s;
    return nullptr;
}

void denoise(Isa isa, const DenoiseSettings& settings, const DenoiseCall& in,
             DenoiseHistory* history, bool reset, DenoiseScratch& scratch, int threads,
             std::vector<DenoisePassTime>* times) {
    const DenoiseRun run(isa, settings, in, history, reset, scratch, threads);
    PassTimes pt(times);
    // Each step its own loop over the tiles (the renderer's scheduler fuses those the frame
    // graph chains).
    for (const DenoiseStep& s : run.steps())
        pt.run(std::string(s.name).c_str(), [&] {
            if (s.setUp) s.setUp();
            parallelForTiles(run.grid().count(), threads, s.tile);
            if (s.finish) s.finish();
        });
}

}  // namespace ssrt
