#include "cli/profile_file.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "trace/trace_types.h"

namespace ssrt {

ProfileFile::ProfileFile() : start_(ProfileClock::now()) {
    threads_.push_back(std::this_thread::get_id());  // tid 1: the caller's
}

double ProfileFile::micros(ProfileClock::time_point t) const {
    return std::chrono::duration<double, std::micro>(t - start_).count();
}

int ProfileFile::tidOf(std::thread::id thread) {
    const auto it = std::find(threads_.begin(), threads_.end(), thread);
    if (it != threads_.end()) return int(it - threads_.begin()) + 1;
    threads_.push_back(thread);
    return int(threads_.size());
}

void ProfileFile::slice(std::string_view name, std::thread::id thread,
                        ProfileClock::time_point begin, ProfileClock::time_point end) {
    const double ts = micros(begin), dur = micros(end) - ts;
    const std::lock_guard lock(mutex_);
    events_.push_back({std::string(name), tidOf(thread), ts, dur});
}

void ProfileFile::counters(const FrameStats& stats, ProfileClock::time_point at) {
    const std::lock_guard lock(mutex_);
    const std::pair<const char*, const TraceStats*> passes[2] = {{"ssr march", &stats.ssr},
                                                                 {"ssgi march", &stats.ssgi}};
    for (const auto& [name, t] : passes) {
        if (!t->ran) continue;
        const MarchStats& m = t->march;
        Counter c{name, micros(at), {}};
        c.values.push_back({"steps", double(m.steps)});
        c.values.push_back({"lanes active %", 100.0 * m.laneUtilisation()});
        for (int e = 0; e < kMarchEndCount; ++e)
            if (MarchEnd(e) != MarchEnd::NoRay)
                c.values.push_back({std::string(marchEndName(MarchEnd(e))), double(m.ends[e])});
        counters_.push_back(std::move(c));
    }
}

std::string ProfileFile::text() const {
    using Json = nlohmann::ordered_json;
    const std::lock_guard lock(mutex_);
    Json events = Json::array();
    events.push_back({{"name", "process_name"},
                      {"ph", "M"},
                      {"pid", 1},
                      {"tid", 1},
                      {"args", {{"name", "ssrt render"}}}});
    for (std::size_t i = 0; i < threads_.size(); ++i)
        events.push_back(
            {{"name", "thread_name"},
             {"ph", "M"},
             {"pid", 1},
             {"tid", int(i) + 1},
             {"args", {{"name", i == 0 ? std::string("main") : "worker " + std::to_string(i)}}}});
    // Each thread's slices by start, the longer first at one start: as a viewer nests them.
    std::vector<const Event*> order;
    for (const Event& e : events_) order.push_back(&e);
    std::stable_sort(order.begin(), order.end(), [](const Event* a, const Event* b) {
        return a->tid != b->tid ? a->tid < b->tid
               : a->ts != b->ts ? a->ts < b->ts
                                : a->dur > b->dur;
    });
    for (const Event* e : order) {
        Json j = {{"name", e->name}, {"ph", "X"},   {"pid", 1},
                  {"tid", e->tid},   {"ts", e->ts}, {"dur", e->dur}};
        // "frame I": the frame's index as an argument too (a 32-bit index: warm-up frames
        // count back from 2^32 - 1, cli/sequence.h)
        if (e->name.rfind("frame ", 0) == 0)
            j["args"] = {{"frame", std::stoull(e->name.substr(6))}};
        events.push_back(std::move(j));
    }
    for (const Counter& c : counters_) {
        Json args = Json::object();
        for (const auto& [k, v] : c.values) args[k] = v;
        events.push_back(
            {{"name", c.name}, {"ph", "C"}, {"pid", 1}, {"ts", c.ts}, {"args", std::move(args)}});
    }
    return Json{{"traceEvents", std::move(events)}, {"displayTimeUnit", "ms"}}.dump(1) + "\n";
}

}  // namespace ssrt
