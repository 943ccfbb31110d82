// Wall-clock times of a frame's passes, for FrameStats::passes (`ssrt render --stats`).
#pragma once

#include <chrono>
#include <string_view>

#include "core/profile.h"
#include "renderer/frame.h"

namespace ssrt {

using PassClock = std::chrono::steady_clock;

inline double msSince(PassClock::time_point t0) {
    return std::chrono::duration<double, std::milli>(PassClock::now() - t0).count();
}

// Times the scope it lives in as one pass (and a slice of the profile: core/profile.h).
class ScopedPass {
public:
    ScopedPass(FrameStats& stats, const char* name) : stats_(stats), name_(name), slice_(name) {}
    ~ScopedPass() { stats_.passes.push_back({name_, msSince(t0_)}); }
    ScopedPass(const ScopedPass&) = delete;
    ScopedPass& operator=(const ScopedPass&) = delete;

private:
    FrameStats& stats_;
    const char* name_;
    ProfileScope slice_;
    PassClock::time_point t0_ = PassClock::now();
};

// Adds the time fn() takes to `ms` (a pass that runs once per sample).
template <class Fn>
void addTime(double& ms, Fn&& fn) {
    const auto t0 = PassClock::now();
    fn();
    ms += msSince(t0);
}
// The same, as a slice of the profile called `name`.
template <class Fn>
void addTime(double& ms, std::string_view name, Fn&& fn) {
    const ProfileScope slice(name);
    addTime(ms, fn);
}

}  // namespace ssrt
