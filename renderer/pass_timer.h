// Wall-clock times of a frame's passes, for FrameStats::passes (`ssrt render --stats`).
#pragma once

#include <chrono>
#include <vector>

#include "renderer/frame.h"

namespace ssrt {

using PassClock = std::chrono::steady_clock;

inline double msSince(PassClock::time_point t0) {
    return std::chrono::duration<double, std::milli>(PassClock::now() - t0).count();
}

// Times the scope it lives in as one pass.
class ScopedPass {
public:
    ScopedPass(FrameStats& stats, const char* name) : stats_(stats), name_(name) {}
    ~ScopedPass() { stats_.passes.push_back({name_, msSince(t0_)}); }
    ScopedPass(const ScopedPass&) = delete;
    ScopedPass& operator=(const ScopedPass&) = delete;

private:
    FrameStats& stats_;
    const char* name_;
    PassClock::time_point t0_ = PassClock::now();
};

// Adds the time fn() takes to `ms` (a pass that runs once per sample).
template <class Fn>
void addTime(double& ms, Fn&& fn) {
    const auto t0 = PassClock::now();
    fn();
    ms += msSince(t0);
}

// The clock of fused stages that run one tile after another inside one parallel loop: each
// stage's time per tile (a slot of its own per tile and stage, so threads never share one),
// plus its serial set-up. report() splits the loop's wall time between the stages by their
// share of the threads' time, so the stages keep their own lines in FrameStats::passes and
// those lines still sum to the wall time.
class StageClock {
public:
    StageClock(int tiles, int stages)
        : stages_(stages),
          tileMs_(std::size_t(tiles) * std::size_t(stages), 0.0),
          setUpMs_(std::size_t(stages), 0.0) {}
    template <class Fn>
    void addSetUp(int stage, Fn&& fn) {
        addTime(setUpMs_[std::size_t(stage)], fn);
    }
    template <class Fn>
    void time(int tile, int stage, Fn&& fn) {
        addTime(tileMs_[std::size_t(tile) * std::size_t(stages_) + std::size_t(stage)], fn);
    }
    // wallMs: the whole of the set-ups and the loop. Stages not `ran` get no line.
    void report(double wallMs, const char* const* names, const bool* ran, FrameStats& stats) const {
        std::vector<double> busy(std::size_t(stages_), 0.0);
        for (std::size_t i = 0; i < tileMs_.size(); ++i)
            busy[i % std::size_t(stages_)] += tileMs_[i];
        double setUp = 0.0, total = 0.0;
        int ranCount = 0;
        for (int s = 0; s < stages_; ++s) {
            setUp += setUpMs_[std::size_t(s)];
            total += busy[std::size_t(s)];
            ranCount += ran[s] ? 1 : 0;
        }
        const double loopMs = wallMs - setUp;
        for (int s = 0; s < stages_; ++s) {
            if (!ran[s]) continue;
            // (A loop too short for the clock to see: equal shares.)
            const double share = total > 0.0 ? busy[std::size_t(s)] / total : 1.0 / ranCount;
            stats.passes.push_back({names[s], setUpMs_[std::size_t(s)] + loopMs * share});
        }
    }

private:
    int stages_;
    std::vector<double> tileMs_;
    std::vector<double> setUpMs_;
};

}  // namespace ssrt
