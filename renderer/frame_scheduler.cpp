#include "renderer/frame_scheduler.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>

#include "renderer/frame_memory.h"
#include "renderer/pass_timer.h"
#include "renderer/render_cancel.h"

namespace ssrt {

namespace {

void checkNew(const std::vector<FrameScheduler::Pass>& passes, std::string_view name) {
    for (const FrameScheduler::Pass& p : passes)
        if (p.name == name)
            throw std::logic_error("frame scheduler: pass '" + std::string(name) + "' given twice");
}

}  // namespace

void FrameScheduler::whole(std::string_view pass, std::function<void()> run,
                           std::string_view through) {
    checkNew(passes_, pass);
    passes_.push_back({pass, through.empty() ? pass : through, std::move(run), {}, {}, {}});
}

void FrameScheduler::tiled(std::string_view pass, std::function<void(int)> tile,
                           std::function<void()> setUp, std::function<void()> finish,
                           const TileGrid* grid) {
    checkNew(passes_, pass);
    passes_.push_back({pass, pass, {}, std::move(setUp), std::move(finish), std::move(tile), grid});
}

// The chain's set-ups in order, then one loop over the tiles, each tile through every pass,
// then the finishes in order. Each pass's time is its busy time over the tiles, scaled so that
// the passes add up to the loop's wall time (the threads' time shared out as they spent it).
void FrameScheduler::runChain(const std::vector<const Pass*>& chain, FrameStats& stats) {
    using Clock = std::chrono::steady_clock;
    // The profile's slices (core/profile.h): the chain's on this thread, its passes' set-ups
    // and finishes in it, and each tile's passes on the thread that runs the tile.
    std::string name(chain[0]->name);
    for (std::size_t i = 1; i < chain.size(); ++i) name += " + " + std::string(chain[i]->name);
    std::vector<std::string> setUps, finishes;
    for (const Pass* p : chain)
        setUps.push_back(std::string(p->name) + " set-up"),
            finishes.push_back(std::string(p->name) + " finish");
    const ProfileScope scope(name);
    ProfileSink* const sink = profileSink();
    std::vector<double> setUpMs(chain.size(), 0.0);
    for (std::size_t i = 0; i < chain.size(); ++i)
        if (chain[i]->setUp) addTime(setUpMs[i], setUps[i], chain[i]->setUp);
    // (After the set-ups, which may make the tiles a pass runs on.)
    const TileGrid& grid = chain[0]->grid ? *chain[0]->grid : grid_;
    for (const Pass* p : chain)
        if (const TileGrid& g = p->grid ? *p->grid : grid_;
            g.width != grid.width || g.height != grid.height)
            throw std::logic_error("frame scheduler: '" + std::string(p->name) +
                                   "' is on other tiles than its chain's first pass");
    const Clock::time_point t1 = Clock::now();
    const std::size_t n = chain.size();
    std::vector<double> busy(std::size_t(grid.count()) * n, 0.0);
    parallelForTiles(grid.count(), threads_, [&](int tile) {
        Clock::time_point a = Clock::now();
        for (std::size_t i = 0; i < n; ++i) {
            chain[i]->tile(tile);
            const Clock::time_point b = Clock::now();
            if (sink) sink->slice(chain[i]->name, std::this_thread::get_id(), a, b);
            busy[std::size_t(tile) * n + i] =
                std::chrono::duration<double, std::milli>(b - a).count();
            a = b;
        }
    });
    const double wall = std::chrono::duration<double, std::milli>(Clock::now() - t1).count();
    std::vector<double> ms(n, 0.0);
    double sum = 0.0;
    for (std::size_t t = 0; t < std::size_t(grid.count()); ++t)
        for (std::size_t i = 0; i < n; ++i) ms[i] += busy[t * n + i], sum += busy[t * n + i];
    const double k = sum > 0.0 ? wall / sum : 0.0;
    for (std::size_t i = 0; i < n; ++i)
        if (chain[i]->finish) addTime(setUpMs[i], finishes[i], chain[i]->finish);
    for (std::size_t i = 0; i < n; ++i)
        stats.passes.push_back({std::string(chain[i]->name), setUpMs[i] + ms[i] * k, i > 0});
}

void FrameScheduler::step(std::string_view last, const std::function<void()>& fn) {
    if (memory_) memory_->step(last, fn);
    else fn();
}

void FrameScheduler::run(FrameStats& stats) {
    for (const Pass& p : passes_) {
        const auto d = std::find_if(passDecls().begin(), passDecls().end(),
                                    [&](const PassDecl& x) { return x.name == p.name; });
        if (d == passDecls().end())
            throw std::logic_error("frame scheduler: no pass '" + std::string(p.name) +
                                   "' in the frame graph");
        if (d->tiled != bool(p.tile))
            throw std::logic_error("frame scheduler: '" + std::string(p.name) + "' is declared " +
                                   (d->tiled ? "tiled" : "whole") + ", given " +
                                   (p.tile ? "tiled" : "whole"));
    }
    std::vector<const Pass*> chain;
    int chainId = -1;
    const auto flush = [&] {
        if (chain.empty()) return;
        stopIfCancelled(cancel_);
        step(chain.back()->name, [&] { runChain(chain, stats); });
        chain.clear();
    };
    for (const GraphPass& g : graph_.passes) {
        const auto p = std::find_if(passes_.begin(), passes_.end(),
                                    [&](const Pass& q) { return q.name == g.decl->name; });
        if (p == passes_.end()) {  // (run elsewhere: a chain does not reach across it)
            flush();
            continue;
        }
        if (p->whole) {
            flush();
            stopIfCancelled(cancel_);
            const ProfileScope scope(p->name);
            step(p->through, p->whole);
            continue;
        }
        if (g.chain != chainId) flush();
        chainId = g.chain;
        chain.push_back(&*p);
    }
    flush();
}

}  // namespace ssrt
