#include "core/profile.h"

#include <cstdlib>
#include <string>

// Valgrind's client requests, where CMake found its headers (core/sources.cmake says why it,
// not __has_include, decides); they are macros that do nothing outside valgrind. Without them
// the scopes never mark.
#if defined(SSRT_CALLGRIND) && SSRT_CALLGRIND
#include <valgrind/callgrind.h>
#define SSRT_HAS_CALLGRIND 1
#else
#define SSRT_HAS_CALLGRIND 0
#endif

namespace ssrt {

namespace {

thread_local ProfileSink* tSink = nullptr;
thread_local std::string_view tScope;

// Under callgrind with SSRT_CALLGRIND_SCOPES set: every scope the first thread to open one
// opens (the command's, which waits for each pass's tiles) dumps callgrind's counts as it
// begins and ends, named "begin NAME" and "end NAME", so that perf/callgrind_passes.py can sum
// the instructions of each pass, every thread's, between its two marks. Outside that, one
// test of a flag per scope.
bool callgrindScopes() {
#if SSRT_HAS_CALLGRIND
    static const bool on = RUNNING_ON_VALGRIND && std::getenv("SSRT_CALLGRIND_SCOPES") != nullptr;
    return on;
#else
    return false;
#endif
}

void callgrindMark([[maybe_unused]] const char* what, [[maybe_unused]] std::string_view name) {
#if SSRT_HAS_CALLGRIND
    static const std::thread::id marking = std::this_thread::get_id();
    if (std::this_thread::get_id() != marking) return;
    const std::string label = std::string(what) + " " + std::string(name);
    CALLGRIND_DUMP_STATS_AT(label.c_str());
#endif
}

}  // namespace

ProfileSink* profileSink() { return tSink; }
std::string_view profileScopeName() { return tScope; }

ProfileTarget::ProfileTarget(ProfileSink* sink) : previous_(tSink) { tSink = sink; }
ProfileTarget::~ProfileTarget() { tSink = previous_; }

ProfileScope::ProfileScope(std::string_view name)
    : sink_(name == tScope ? nullptr : tSink), name_(name), outer_(tScope) {
    if (callgrindScopes()) callgrindMark("begin", name_);
    if (!sink_) return;
    tScope = name;
    begin_ = ProfileClock::now();
}

ProfileScope::~ProfileScope() {
    if (callgrindScopes()) callgrindMark("end", name_);
    if (!sink_) return;
    sink_->slice(name_, std::this_thread::get_id(), begin_, ProfileClock::now());
    tScope = outer_;
}

}  // namespace ssrt
