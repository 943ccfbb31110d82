// `ssrt render --profile FILE`: the slices a render records (core/profile.h) as a Chrome
// trace-event file, which Perfetto (ui.perfetto.dev) and chrome://tracing open: one complete
// event ("ph": "X") per slice, in microseconds since the first render started, on a thread
// numbered in the order threads first recorded (1: the thread that called the render, named
// "main"; the rest "worker N"); each frame's "frame I" slice carries the frame's index; the
// march's counters of each frame ("ph": "C": steps, lanes active, how rays ended) as counter
// tracks at the end of the frame's render call.
#pragma once

#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "core/profile.h"
#include "renderer/frame.h"

namespace ssrt {

class ProfileFile final : public ProfileSink {
public:
    ProfileFile();
    void slice(std::string_view name, std::thread::id thread, ProfileClock::time_point begin,
               ProfileClock::time_point end) override;
    // Frame `index`'s march counters, at `at` (its render call's end).
    void counters(const FrameStats& stats, ProfileClock::time_point at);
    // The file's text (JSON: {"traceEvents": [...], "displayTimeUnit": "ms"}).
    std::string text() const;

private:
    struct Event {
        std::string name;
        int tid;
        double ts, dur;  // microseconds
    };
    struct Counter {
        std::string name;
        double ts;
        std::vector<std::pair<std::string, double>> values;
    };
    int tidOf(std::thread::id thread);  // (under mutex_)
    double micros(ProfileClock::time_point t) const;

    ProfileClock::time_point start_;
    mutable std::mutex mutex_;
    std::vector<std::thread::id> threads_;  // tid - 1
    std::vector<Event> events_;
    std::vector<Counter> counters_;
};

}  // namespace ssrt
