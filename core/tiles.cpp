#include "core/tiles.h"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <string>
#include <thread>
#include <vector>

#include "core/profile.h"

namespace ssrt {

TileRect TileGrid::rect(int tile) const { return tileRect(tile, tilesX, width, height); }

namespace {

void runParallel(int count, int threads, const std::function<void(int)>& fn) {
    if (threads == 1) {
        for (int i = 0; i < count; ++i) fn(i);
        return;
    }
    auto body = [&] {
        // simple_partitioner with grain 1: every index is its own task; no index ever
        // sees state from another, so the order TBB picks cannot matter.
        tbb::parallel_for(
            tbb::blocked_range<int>(0, count, 1),
            [&](const tbb::blocked_range<int>& r) {
                for (int i = r.begin(); i != r.end(); ++i) fn(i);
            },
            tbb::simple_partitioner());
    };
    if (threads <= 0) {
        body();
    } else {
        tbb::task_arena arena(threads);
        arena.execute(body);
    }
}

// With a profile sink on the calling thread (core/profile.h): each index a slice on the
// thread that ran it ("<scope> tile", or "<scope> part"), and on every other thread that took
// part one slice of the scope's name from its first index to its last, so that the thread's
// slices nest as the calling thread's do under its scope.
void runProfiled(ProfileSink& sink, int count, int threads, const std::function<void(int)>& fn,
                 const char* what) {
    struct Span {
        std::thread::id thread;
        ProfileClock::time_point begin, end;
    };
    std::vector<Span> spans(static_cast<std::size_t>(count));
    runParallel(count, threads, [&](int i) {
        const ProfileClock::time_point a = ProfileClock::now();
        fn(i);
        spans[std::size_t(i)] = {std::this_thread::get_id(), a, ProfileClock::now()};
    });
    const std::string_view scope = profileScopeName().empty() ? "loop" : profileScopeName();
    const std::string each = std::string(scope) + " " + what;
    const std::thread::id caller = std::this_thread::get_id();
    std::vector<Span> others;  // per thread but the caller's: its first begin and last end
    for (const Span& s : spans) {
        sink.slice(each, s.thread, s.begin, s.end);
        if (s.thread == caller) continue;
        const auto o = std::find_if(others.begin(), others.end(),
                                    [&](const Span& x) { return x.thread == s.thread; });
        if (o == others.end()) {
            others.push_back(s);
        } else {
            o->begin = std::min(o->begin, s.begin);
            o->end = std::max(o->end, s.end);
        }
    }
    for (const Span& o : others) sink.slice(scope, o.thread, o.begin, o.end);
}

}  // namespace

void parallelFor(int count, int threads, const std::function<void(int)>& fn) {
    if (count <= 0) return;
    if (ProfileSink* sink = profileSink()) runProfiled(*sink, count, threads, fn, "part");
    else runParallel(count, threads, fn);
}

void parallelForTiles(int tileCount, int threads, const std::function<void(int)>& fn) {
    if (tileCount <= 0) return;
    if (ProfileSink* sink = profileSink()) runProfiled(*sink, tileCount, threads, fn, "tile");
    else runParallel(tileCount, threads, fn);
}

}  // namespace ssrt
